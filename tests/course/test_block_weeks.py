"""A later week may declare a new block where an earlier week had one (week 7's automaton in
QBSupervisor.execute, where week 5's switching was): in each week the block of the latest week up to it
is the one meant, for the stubs, the handout check and migrate alike."""

from __future__ import annotations

import pytest

from simiam.course import weeks
from simiam.course.placeholders import Placeholder
from simiam.course.stubs import stub_text
from simiam.course.weeks import placeholder_for

KEY = ("qb_supervisor.py", "QBSupervisor.execute")
EARLY = Placeholder(*KEY, hint="week 5's switching", code="pass", week=5)
LATE = Placeholder(*KEY, hint="week 7's automaton", code="pass", week=7)
SOLUTION = "def execute():\n    # START CODE BLOCK\n    state = 1\n    # END CODE BLOCK\n    return state\n"


@pytest.fixture
def two_weeks(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("simiam.course.weeks.all_blocks", lambda: (EARLY, LATE))
    assert weeks.placeholder_for is placeholder_for


@pytest.mark.usefixtures("two_weeks")
@pytest.mark.parametrize(("week", "meant"), [(5, EARLY), (6, EARLY), (7, LATE), (8, LATE), (None, EARLY)])
def test_the_latest_block_up_to_the_week_is_meant(week, meant):
    assert placeholder_for(*KEY, 1, week) is meant


@pytest.mark.usefixtures("two_weeks")
def test_a_stub_gets_its_own_weeks_placeholder_and_ships_the_earlier_block_filled():
    week7, rows7 = stub_text(7, _in_class(SOLUTION), "qb_supervisor.py")
    assert "week 7's automaton" in week7 and "state = 1" not in week7 and rows7[0]["week"] == 7
    week6, rows6 = stub_text(6, _in_class(SOLUTION), "qb_supervisor.py")
    assert "state = 1" in week6 and rows6[0]["week"] == 5  # week 5's block, shipped filled in week 6


@pytest.mark.usefixtures("two_weeks")
def test_a_block_of_a_later_week_only_is_still_refused():
    with pytest.raises(Exception, match="new in week 5"):
        stub_text(4, _in_class(SOLUTION), "qb_supervisor.py")


def _in_class(function_text: str) -> str:
    body = "".join(f"    {ln}\n" if ln else "\n" for ln in function_text.splitlines())
    return "class QBSupervisor:\n" + body
