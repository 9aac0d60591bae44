"""Wrong version of grader.grading._open_session (issue 30, item 2): the second worker a week 5-7 grading
opens for earlier weeks' blocks starts with a fresh time budget of its own, so one grading could use twice
the documented total. Caught by tests/grader/test_one_budget.py."""

from __future__ import annotations

from pathlib import Path

from grader.sandbox.session import StudentSession


def open_session_with_a_fresh_budget(job, folder: Path, others: list) -> StudentSession:
    other = StudentSession(job.week, folder, job.limits, sandbox=job.sandbox, official=job.official)
    others.append(other)
    other.start()
    return other
