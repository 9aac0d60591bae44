"""A week's parts agree (issue 33): the week's declaration (simiam/course/weeks/weekN.py), its checks
(grader/checks/), and the probes they send into the sandbox (grader/inside/probes_weekN.py, registered in
grader/inside/probes.py). Every probe a check sends exists in the sandbox, every probe is sent by some
check, every probe says which student code it runs, and that code is a block the week (or an earlier one)
declares, in a file the check needs. So adding a week fails here, naming the missing part, rather than in
a grading. How the probes a check sends are found: tests/course/week_parts.py.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest
from week_parts import probes_sent, problems, undeclared, unsent

from grader.checks import checks_for_week
from grader.inside.probes import PROBES
from simiam.course.weeks import all_weeks, get_week, week_numbers

WRONG = Path(__file__).resolve().parents[1] / "data" / "week_parts"


def _wrong(name: str) -> ModuleType:
    """A module of tests/data/week_parts/, imported under a name of its own (the analysis reads its source
    through sys.modules, as it does the grader's)."""
    spec = importlib.util.spec_from_file_location(f"week_parts_wrong_{name}", WRONG / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("week", week_numbers(), ids=[f"week{n}" for n in week_numbers()])
def test_a_weeks_checks_probes_and_blocks_agree(week: int) -> None:
    assert problems(get_week(week), all_weeks(), checks_for_week(week), PROBES) == []


def test_every_probe_is_sent_by_some_check_and_says_what_it_runs() -> None:
    every = [check for week in week_numbers() for check in checks_for_week(week)]
    assert unsent(PROBES, every) == []
    assert undeclared(PROBES) == []


def test_the_checks_of_a_week_are_read_as_sending_their_probes() -> None:
    """The reading itself: ensure_w's checks send ensure_w (written in the week's module), the PID checks
    go_to_goal (written in grader/checks/pid.py), the scenario checks none."""
    sent = {check.id: probes_sent(check.run)[0] for check in checks_for_week(3)}
    assert sent["week3.ensure_w.keeps_w"] == {"ensure_w"}, sent
    assert sent["week3.pid.proportional"] == {"go_to_goal"}, sent
    assert sent["week3.pid.settle_time"] == set(), sent


def test_a_week_missing_a_block_is_caught() -> None:
    week = _wrong("week3_missing_block").WEEK
    weeks = [week if w.number == 3 else w for w in all_weeks()]
    found = problems(week, weeks, checks_for_week(3), PROBES)
    assert found, "a week without the ensure_w block passed"
    assert all("qb_supervisor.py:QBSupervisor.ensure_w" in line and "no week up to 3" in line
               for line in found), found
    assert {line.split("check ")[1].split(" ")[0] for line in found} == {
        "week3.ensure_w.keeps_w", "week3.ensure_w.max_vel", "week3.ensure_w.gives_up_v"}, found


def test_a_check_sending_a_missing_probe_is_caught() -> None:
    checks = _wrong("checks_missing_probe").CHECKS
    found = problems(get_week(3), all_weeks(), checks, PROBES)
    assert len(found) == 2, found
    assert "check week3.go_to_goal.theta_g sends probe 'go_to_goal_fast', which the sandbox has not" \
        in found[0]
    assert "check week3.go_to_goal.by_name" in found[1] and "a probe named by an expression" in found[1]


def test_a_probe_no_check_sends_and_one_without_its_student_code_are_caught() -> None:
    wrong = _wrong("probe_nobody_sends")
    probes = {**PROBES, "week3_heading": wrong.week3_heading, "week3_speeds": wrong.week3_speeds}
    every = [check for week in week_numbers() for check in checks_for_week(week)]
    assert [line.split("'")[1] for line in unsent(probes, every)] == ["week3_heading", "week3_speeds"]
    assert [line.split("'")[1] for line in undeclared(probes)] == ["week3_speeds"]


def test_a_probe_running_a_file_its_check_does_not_need_is_caught() -> None:
    """ensure_w's checks need only qb_supervisor.py; a probe that ran go_to_goal.py's GoToGoal.execute
    would run a file that may have failed to load."""
    wrong = dict(PROBES)

    def ensure_w(sub, week: int, v: float, w: float) -> None:
        return None

    ensure_w.exercises = ("go_to_goal.py:GoToGoal.execute",)  # type: ignore[attr-defined]
    wrong["ensure_w"] = ensure_w
    found = problems(get_week(3), all_weeks(), checks_for_week(3), wrong)
    assert len(found) == 3 and all("leave out go_to_goal.py" in line for line in found), found
