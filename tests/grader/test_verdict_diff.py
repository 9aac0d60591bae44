"""A failing verdict comparison prints what differed: the whole verdict, and each changed check with its
expected and given verdict and its message (tests/grader/verdict_diff.py, used by test_checks_fail.py and
test_under_load.py)."""

from __future__ import annotations

from verdict_diff import differences


def _result(status: str, points: float, message: str) -> dict:
    return {"submission": "solutions/week6", "week": 6, "seed": 2014, "status": "graded",
            "checks": [{"id": "week6.laps.left", "status": status, "points": points, "message": message},
                       {"id": "week6.laps.right", "status": "passed", "points": 1.0, "message": ""}]}


EXPECTED = {"week6.laps.left": ["passed", 2.0], "week6.laps.right": ["passed", 1.0]}


def test_the_same_verdict_prints_nothing() -> None:
    assert differences(_result("passed", 2.0, ""), EXPECTED) == ""


def test_a_changed_check_prints_the_whole_verdict_and_its_message() -> None:
    text = differences(_result("timeout", 0.0, "at t = 40.95 s your code did not answer in time"), EXPECTED)
    print(text)
    assert '"week6.laps.right": ["passed", 1.0]' in text  # the whole verdict, unchanged checks too
    assert ("week6.laps.left: expected ['passed', 2.0], got ['timeout', 0.0]: at t = 40.95 s your code did "
            "not answer in time") in text
    assert "week6.laps.right: expected" not in text  # only what differs gets a line of its own


def test_a_check_missing_from_the_result_is_named() -> None:
    result = _result("passed", 2.0, "")
    result["checks"].pop()
    assert "week6.laps.right: expected ['passed', 1.0], got None: (not run)" in differences(result, EXPECTED)
