"""Shared by every test area: this folder is on sys.path, so `mistakes` (wrong versions built from
solutions/ plus a small patch) imports from tests/grader, tests/course and tests/fidelity alike."""

import sys

import pytest

# Before any test module imports numpy: the numeric environment every run of controller code uses (one
# BLAS kernel, one thread, one SIMD level; simiam.numerics). pytest's own plugins do not import numpy.
assert "numpy" not in sys.modules, "numpy was imported before simiam could pin the numeric environment"
import simiam  # noqa: E402,F401

# isort: split
# Without bubblewrap, a test skipped for want of it must be marked `sandbox` (tests/mode_audit.py).
from mode_audit import pytest_runtest_makereport  # noqa: E402,F401


@pytest.hookimpl(tryfirst=True, optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: object) -> object | None:
    """`--dist loadscope` with the heaviest modules handed out first (tests/heaviest_first.py)."""
    if config.getvalue("dist") != "loadscope":
        return None
    from heaviest_first import HeaviestFirst

    return HeaviestFirst(config, log)
