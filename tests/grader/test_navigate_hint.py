"""Week 7's navigation hint says what the run's trace shows (issue 31): d_prog stuck because progress_made
always held (set_progress_point never lowers it) is not d_prog stuck because progress_made never held again
(a strict < set once at the start: a real student's). The first pattern is also graded from the kept
version week7_progress_point_never_set (tests/grader/test_checks_fail.py)."""

from __future__ import annotations

from types import SimpleNamespace

from grader.checks.week7 import NAVIGATE_HINT, navigate_hint


def _run(d_prog: list, progress: list) -> SimpleNamespace:
    return SimpleNamespace(trace=SimpleNamespace(steps={"d_prog": d_prog, "progress_made": progress}))


def test_d_prog_set_once_then_never_progress_is_not_called_never_set() -> None:
    # the real student's trace: set_progress_point ran at the first step (d_prog 10 -> 1.2728), then a
    # strict < counted no step as progress again
    said = navigate_hint([_run([None] + [1.2727922061357855] * 300, [None, True] + [False] * 299)])
    assert "d_prog stayed at 1.2728 m" in said
    assert "progress_made was False 299 of the 300 times it was checked" in said
    assert "Check progress_made's comparison" in said
    assert "never calls" not in said and "set_progress_point()" not in said


def test_d_prog_never_lowered_while_progress_always_held() -> None:
    said = navigate_hint([_run([None] + [10.0] * 200, [None] + [True] * 200)])
    assert "progress_made held all 200 times it was checked" in said
    assert "calls self.set_progress_point() when it makes progress" in said
    assert "progress_made was False" not in said


def test_a_moving_d_prog_gets_the_general_hint() -> None:
    assert navigate_hint([_run([None, 1.5, 1.4, 1.3], [None, True, True, True])]) == NAVIGATE_HINT
