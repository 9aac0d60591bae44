"""A bug in the grader never reaches a student as a raw exception: a check that crashes, or a grading that
crashes as a whole, says "grader error, not your fault" and asks for a report; the other checks go on."""

from __future__ import annotations

from pathlib import Path

from grader import grading
from grader.checks import GRADER_ERROR, Check, Context, Outcome, run_check
from grader.grading import grade_submission

ROOT = Path(__file__).resolve().parents[2]


def _broken(ctx: Context) -> Outcome:
    return {"a": 1}["b"]  # a grader bug: a KeyError from the grader's own code


def test_a_check_that_crashes_is_a_grader_error_not_the_students() -> None:
    check = Check("week3.x.y", "a check", "property", 1.0, _broken)
    result = run_check(check, Context(week=3, seed=1, session=None), {})
    assert result.status == "error" and result.points == 0
    assert result.message.startswith(GRADER_ERROR)
    assert "KeyError" in result.message and "report it" in result.message
    assert "your other checks are not affected" in result.message
    assert result.details["grader_error"]["type"] == "KeyError"
    # the innermost frame inside the grader package: here the check runner, as the bug is in a test file
    assert result.details["grader_error"]["where"].startswith("checks/__init__.py:")


def test_a_grading_that_crashes_says_so_and_names_no_student_fault(monkeypatch) -> None:
    def crash(*_args, **_kwargs):
        raise RuntimeError("the splicer fell over")

    monkeypatch.setattr(grading, "_splice", crash)
    result = grade_submission(2, ROOT / "solutions" / "week2", seed=1)
    assert result["status"] == "invalid"
    assert result["message"].startswith(GRADER_ERROR) and "RuntimeError" in result["message"]
    assert "your submission could not be graded" in result["message"] and "report it" in result["message"]
    assert result["grader_error"]["where"].startswith("grading.py:")
    assert all(c["status"] == "error" and c["message"] == result["message"] for c in result["checks"])
