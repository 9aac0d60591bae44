"""Shared by every test area: this folder is on sys.path, so `mistakes` (wrong versions built from
solutions/ plus a small patch) imports from tests/grader, tests/course and tests/fidelity alike."""
