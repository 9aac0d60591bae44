"""Issue 30 item 1: numbers in answers are bounded by magnitude (what a float holds), on both sides of the
pipe, so no student value reaches the trusted checks' arithmetic as a number they cannot hold.

The attack (tests/data/attacks/graded/huge_switch_count.patch) makes week 5's switching probe send its
switch count as the integer 2**1024 - 1: 1024 bits, within the former bound by bit count, and too large for
a float. Before, it reached math.isfinite() in grader/checks/week5.py (`_one_switch`) and the check said
"grader error ... OverflowError"; now the worker refuses to send it and the grader's side refuses to read
it, and the check fails with a message the student can read.
"""

from __future__ import annotations

import sys

import mistakes
import pytest

from grader.checks import GRADER_ERROR
from grader.grading import grade_submission
from grader.inside import protocol
from grader.inside.answer_bounds import MAX_NUMBER, OutOfBounds, weigh
from grader.sandbox.limits import Limits

CHECK = "week5.switching.states"
LIMITS = Limits(call_seconds=5.0, total_seconds=60.0)
BIGGEST = int(sys.float_info.max)


@pytest.mark.parametrize("value", [2**1024 - 1, -(2**1024 - 1), BIGGEST + 1, [1.0, {"n": BIGGEST + 1}]],
                         ids=["2**1024-1", "-(2**1024-1)", "float-max+1", "nested"])
def test_integers_no_float_holds_are_refused_on_both_sides(value):
    with pytest.raises(OutOfBounds, match="too large"):
        weigh(value)                                      # the grader's side (grader.sandbox.runner)
    with pytest.raises(protocol.NotJSON, match="too large"):
        protocol.to_json(value)                           # the worker's side


@pytest.mark.parametrize("value", [BIGGEST, -BIGGEST, 10**300, 0, -1],
                         ids=["float-max", "-float-max", "10**300", "0", "-1"])
def test_integers_a_float_holds_pass(value):
    assert MAX_NUMBER == BIGGEST
    weigh(value)
    assert protocol.to_json(value) == value
    float(value)  # what every check may do with a number it was given


def test_a_switch_count_no_float_holds_fails_the_check_not_the_grader(tmp_path, mode):
    folder = mistakes.build("attacks/graded", "huge_switch_count", tmp_path, 5)
    result = grade_submission(5, folder, only=CHECK, limits=LIMITS, sandbox=mode)
    check = {c["id"]: c for c in result["checks"]}[CHECK]
    assert GRADER_ERROR not in check["message"] and "OverflowError" not in check["message"], check["message"]
    assert (check["status"], check["points"]) == ("failed", 0), check
    assert "too large" in check["message"], check["message"]
