"""load_submission: a fresh package per load, and student-readable LoadErrors (file, line, message)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import mistakes
import pytest

from simiam.course.loader import LoadError, load_submission
from simiam.course.weeks import week_numbers

ROOT = Path(__file__).resolve().parents[2]


def _line_of(path: Path, text: str) -> int:
    """1-based line of the first line of `path` containing `text`."""
    return next(i for i, line in enumerate(path.read_text().splitlines(), 1) if text in line)


def _copy(tmp_path: Path, week: int, fixture: str | None = None) -> Path:
    """solutions/weekN, with tests/data/submissions/<fixture> (a .patch or hand-written files) if given."""
    if fixture:
        return mistakes.build("submissions", fixture, tmp_path, week, folder_name=f"week{week}")
    folder = tmp_path / f"week{week}"
    shutil.copytree(ROOT / f"solutions/week{week}", folder)
    return folder


@pytest.mark.parametrize("week", week_numbers())
def test_solutions_load_cleanly(week):
    sub = load_submission(ROOT / f"solutions/week{week}", week)
    assert sub.errors == []
    assert hasattr(sub.module("qb_supervisor"), "QBSupervisor")


def test_syntax_error_names_file_and_line(tmp_path):
    folder = _copy(tmp_path, 3, "loader_syntax_error")
    sub = load_submission(folder, 3)
    line = _line_of(folder / "go_to_goal.py", "theta_g = math.atan2(u_y, u_x")
    assert [(e.file, e.line) for e in sub.errors] == [("go_to_goal.py", line)]  # once, not per importer
    assert "syntax error" in sub.errors[0].message
    assert str(sub.errors[0]).startswith(f"go_to_goal.py:{line}: ")


def test_missing_file(tmp_path):
    folder = _copy(tmp_path, 3)
    (folder / "go_to_goal.py").unlink()
    sub = load_submission(folder, 3)
    files = [e.file for e in sub.errors]
    assert "go_to_goal.py" in files
    missing = next(e for e in sub.errors if e.file == "go_to_goal.py")
    assert "missing file" in missing.message
    # qb_supervisor imports it: that error must not expose the internal package name
    assert all("simiam_submission_" not in e.message for e in sub.errors)


def test_missing_function(tmp_path):
    folder = _copy(tmp_path, 2, "loader_missing_function")
    sub = load_submission(folder, 2)
    assert len(sub.errors) == 1
    err = sub.errors[0]
    assert err.file == "differential_drive.py" and "uni_to_diff" in err.message


def test_import_time_exception_names_file_and_line(tmp_path):
    folder = _copy(tmp_path, 3, "loader_import_exception")
    sub = load_submission(folder, 3)
    line = _line_of(folder / "quickbot.py", "3 / 0")
    assert len(sub.errors) == 1
    assert (sub.errors[0].file, sub.errors[0].line) == ("quickbot.py", line)
    assert "ZeroDivisionError" in sub.errors[0].message


def test_no_such_folder(tmp_path):
    sub = load_submission(tmp_path / "nowhere", 3)
    assert not sub.ok and "no such folder" in sub.errors[0].message


def test_each_load_is_fresh_and_leaves_no_trace(tmp_path):
    folder = _copy(tmp_path, 3)
    path_before = list(sys.path)
    a = load_submission(folder, 3)
    b = load_submission(folder, 3)
    assert a.package != b.package
    assert a.module("go_to_goal").GoToGoal is not b.module("go_to_goal").GoToGoal
    # the supervisor uses the GoToGoal of its own load (relative imports stay inside the package)
    sup = b.module("qb_supervisor").QBSupervisor()
    assert type(sup.controllers["go_to_goal"]) is b.module("go_to_goal").GoToGoal
    assert sys.path == path_before
    assert not list(folder.rglob("__pycache__")) and not list(folder.rglob("*.pyc"))
    a.unload()
    assert a.package not in sys.modules


def test_load_error_json():
    err = LoadError("quickbot.py", 3, "boom")
    assert err.to_json() == {"file": "quickbot.py", "line": 3, "message": "boom"}
    assert str(LoadError("quickbot.py", None, "missing")) == "quickbot.py: missing"
