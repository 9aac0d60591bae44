"""End to end: a student's endless loop inside a code block is reported with its file, line and method, in
the check's message, the terminal table and the HTML report."""

from __future__ import annotations

import io
from pathlib import Path

import mistakes
import pytest

from grader.cli import print_result
from grader.grading import grade_submission
from grader.sandbox.isolation import BWRAP, SUBPROCESS, bwrap_works
from grader.sandbox.limits import Limits

# 0.5 s per call is far above what must answer in it: the loop is hit at the first step, so only loading and
# brain_start do, in milliseconds (at most 0.03 s measured with both cores saturated by busy loops).
FAST = Limits(call_seconds=0.5, total_seconds=20.0)


def build(name: str, week: int, into: Path) -> Path:
    """solutions/weekN with tests/data/stuck/<name>.patch applied."""
    return mistakes.build("stuck", name, into, week, folder_name=f"week{week}")


def stuck_line(folder: Path, file: str) -> int:
    lines = (folder / file).read_text().splitlines()
    return next(i for i, text in enumerate(lines, 1) if "# STUCK" in text)


def test_a_loop_in_go_to_goal_execute_is_named_in_the_message_table_and_report(tmp_path: Path) -> None:
    folder = build("week3_endless_loop", 3, tmp_path)
    where = f"go_to_goal.py:{stuck_line(folder, 'go_to_goal.py')} in GoToGoal.execute"
    result = grade_submission(3, folder, seed=1, only="week3.go_to_goal.reach_goals", limits=FAST,
                              out_dir=tmp_path / "out")
    check = result["checks"][0]
    print(check["message"])
    assert check["status"] == "timeout" and check["points"] == 0
    assert (f"your code did not answer in time: no answer within 0.5 s, the time limit per call; "
            f"it was still running at {where} (an endless loop or a long wait?)") in check["message"]
    table = io.StringIO()
    print_result(result, table)
    assert where in " ".join(table.getvalue().split())  # the table wraps long messages
    assert where in (tmp_path / "out" / "week3.html").read_text()


@pytest.mark.parametrize("mode", [
    pytest.param(BWRAP, marks=[pytest.mark.sandbox,
                               pytest.mark.skipif(not bwrap_works()[0], reason=bwrap_works()[1])]),
    SUBPROCESS])
def test_a_loop_in_uni_to_diff_is_named_in_the_property_message(tmp_path: Path, mode: str) -> None:
    folder = build("week2_endless_loop", 2, tmp_path)
    line = stuck_line(folder, "differential_drive.py")
    result = grade_submission(2, folder, seed=1, only="week2.uni_to_diff.straight", limits=FAST, sandbox=mode)
    check = result["checks"][0]
    print(check["message"])
    assert check["status"] == "timeout"
    assert check["message"] == ("your code did not answer in time: no answer within 2 s, the time limit per "
                                f"call; it was still running at differential_drive.py:{line} in uni_to_diff "
                                "(an endless loop or a long wait?)")
