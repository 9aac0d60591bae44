"""A file the student writes nothing in this week may be missing from a submission: the version the course
ships is used, and the feedback says so. A missing file the student had to write fails its checks."""

from __future__ import annotations

import shutil
from pathlib import Path

from grader.grading import files_to_write, grade_submission

ROOT = Path(__file__).resolve().parents[2]


def _without(tmp_path: Path, week: int, *names: str) -> Path:
    folder = tmp_path / f"week{week}"
    shutil.copytree(ROOT / "solutions" / f"week{week}", folder)
    for name in names:
        (folder / name).unlink()
    return folder


def test_the_files_to_write_are_the_weeks_new_blocks() -> None:
    assert files_to_write(2) == {"differential_drive.py", "qb_supervisor.py", "quickbot.py"}
    assert files_to_write(3) == {"go_to_goal.py", "qb_supervisor.py"}
    assert files_to_write(4) == {"avoid_obstacles.py"}


def test_week3_without_the_shipped_differential_drive_keeps_full_marks(tmp_path: Path) -> None:
    result = grade_submission(3, _without(tmp_path, 3, "differential_drive.py", "go_to_angle.py"), seed=1)
    assert result["status"] == "graded" and result["score"] == result["max_score"]
    notes = [n for n in result["notices"] if "missing from your submission" in n]
    assert len(notes) == 2 and all("the version the course ships was used" in n for n in notes)


def test_a_missing_file_to_write_fails_the_checks_that_need_it(tmp_path: Path) -> None:
    result = grade_submission(3, _without(tmp_path, 3, "go_to_goal.py"), seed=1)
    failed = {c["id"]: c["message"] for c in result["checks"] if c["status"] != "passed"}
    assert "week3.pid.integral" in failed and "go_to_goal.py is missing" in failed["week3.pid.integral"]
    assert "week3.ensure_w.keeps_w" not in failed


def test_without_the_solutions_at_hand_a_missing_shipped_file_is_named_with_what_to_do(
        tmp_path: Path, monkeypatch) -> None:
    # a student's installed package holds no answers: it cannot rebuild the week-3 differential_drive.py
    # the course shipped (with the week-2 uni_to_diff filled in), so the notice says to copy it back
    import grader.grading as grading

    monkeypatch.setattr(grading, "ROOT", tmp_path / "no-checkout")
    result = grade_submission(3, _without(tmp_path, 3, "differential_drive.py"), seed=1)
    notes = [n for n in result["notices"] if "differential_drive.py is missing" in n]
    assert len(notes) == 1 and "copy differential_drive.py from your week3 handout" in notes[0]
    assert result["score"] < result["max_score"]
