"""Every visible check is proven able to fail by a kept wrong version that aims at it (`# aims:` lines of
tests/data/wrong), as `grade selfcheck`'s coverage line reports: week3.pid.proportional was caught by none
(issue 31) until week3_proportional_gain_twice. The checks still caught by none are listed here, so the
list can only shrink."""

from __future__ import annotations

from mistakes import DATA, read_mistake

from grader.checks import checks_for_week
from simiam.course.weeks import week_numbers

# week 1 grades the untouched stub (nothing to get wrong); the others are still to be given a kept version
CAUGHT_BY_NONE = {"week1.run.headless", "week1.run.stays_still", "week2.uni_to_diff.linearity",
                  "week4.avoid.points_away"}


def test_every_visible_check_but_the_listed_ones_has_a_kept_wrong_version() -> None:
    aimed: set[str] = set()
    for patch in (DATA / "wrong").glob("*.patch"):
        aimed |= set(read_mistake(patch).aims or ())
    visible = {c.id for week in week_numbers() for c in checks_for_week(week) if c.visibility != "hidden"}
    assert visible - aimed == CAUGHT_BY_NONE, sorted((visible - aimed) ^ CAUGHT_BY_NONE)
    assert "week3.pid.proportional" in aimed
