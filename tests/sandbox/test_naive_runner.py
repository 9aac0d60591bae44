"""The attack suite against the wrong design (student code imported into the grading process), run in a
throw-away interpreter: each attack that the sandbox tests show harmless wins here. This is what makes the
sandbox tests able to fail."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from sandbox_helpers import make_submission

NAIVE = Path(__file__).resolve().parent / "sandbox_wrong" / "in_process.py"
REPO = Path(__file__).resolve().parents[2]


def naive(folder: Path, fn: str = "attack", **args) -> subprocess.CompletedProcess:
    argv = [sys.executable, str(NAIVE), str(folder), fn, json.dumps(args)]
    return subprocess.run(argv, capture_output=True, text=True, timeout=60, cwd=REPO)


@pytest.fixture
def base(tmp_path):
    yield tmp_path
    shutil.rmtree(tmp_path, ignore_errors=True)


def test_monkeypatching_compromises_an_in_process_grader(base):
    done = naive(make_submission(base, "monkeypatch"))
    assert "math.sqrt(4) -> 0.0" in done.stdout


def test_a_lying_object_passes_an_in_process_comparison(base):
    done = naive(make_submission(base, "evil_objects"), kind="eq")
    assert "answer == expected -> True" in done.stdout


def test_exit_mid_run_ends_an_in_process_grader_with_status_0(base):
    done = naive(make_submission(base, "os_exit_mid_run"))
    assert done.returncode == 0 and "DONE" not in done.stdout  # an exit-code grader would call it a pass


def test_an_in_process_grader_lets_student_code_read_the_repository(base):
    done = naive(make_submission(base, "read_solutions"), paths=[str(REPO / "pyproject.toml")])
    assert "DONE" in done.stdout and "pyproject.toml" in done.stdout
