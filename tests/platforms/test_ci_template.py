"""docs/ci-selfcheck.yml, the CI template instructors copy, builds the handout of every week the course
declares: a week added to (or dropped from) simiam/course/weeks without the template following fails here."""

from __future__ import annotations

import re

import yaml
from mistakes import ROOT

from simiam.course.weeks import week_numbers

TEMPLATE = ROOT / "docs" / "ci-selfcheck.yml"


def handout_weeks(workflow_text: str) -> list[int]:
    """The weeks whose handout the workflow builds, from its `for week in ...; do grade handout` step."""
    steps = yaml.safe_load(workflow_text)["jobs"]["selfcheck"]["steps"]
    loop = r"for week in ([\d ]+); do grade handout"
    loops = [m for s in steps for m in re.findall(loop, s.get("run", ""))]
    assert len(loops) == 1, f"expected one handout loop in the template, found {loops}"
    return [int(w) for w in loops[0].split()]


def test_the_template_builds_the_handout_of_every_week_of_the_course():
    assert handout_weeks(TEMPLATE.read_text()) == list(week_numbers())


def test_a_template_that_stops_at_week_4_is_caught():
    # the template as it was before issue 23 (weeks 1-4 only): the comparison above must see it
    stale = TEMPLATE.read_text().replace("for week in 1 2 3 4 5 6 7;", "for week in 1 2 3 4;")
    assert handout_weeks(stale) == [1, 2, 3, 4] != list(week_numbers())
