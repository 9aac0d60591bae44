"""WRONG VERSION (tests/sandbox/test_inside.py): what is planted at the end of grader/inside/probes.py: an import by name of a check module planted."""


def _cheat():
    import importlib
    return importlib.import_module("grader.checks.week3")
