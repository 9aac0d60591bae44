"""The instructor's hidden week-7 variants are fair and discriminating: the reference solution reaches every
goal (the TRUE position within 0.05 m, no collision, within the check's 60 s), and with the maker's margins
(by 50 s, never closer than 5 mm to an obstacle) so does the manual's progress rule, while neither the
untouched stub (straight for the goal) nor an automaton that never follows a wall reaches one, from the
declared start and from starts moved by 1e-6 m (instructor_tools/hidden_week7.py tries 1e-9 m too and
every BLAS kernel)."""

from __future__ import annotations

import math
from collections import Counter
from pathlib import Path

import pytest

from grader.checks.week7 import D_GOAL, HIDDEN_SECONDS, turned
from grader.hidden import load_hidden
from grader.hidden.draw import turn_quarter
from instructor_tools.hidden_week7 import NUDGES, fair, folders
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
WEEK = get_week(7)


def outcome(folder: Path, variant: dict) -> tuple:
    """("reached", t), ("collided", t) or ("not reached",), as the check judges one run."""
    world, goal = turned(load_world(WEEK.world), tuple(variant["goal"]), variant["turn"], variant["of"])
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    brain = LocalBrain(sub, WEEK, WEEK.settings.with_changes(goal=goal).as_dict())
    sim = Simulator(world, brain, WEEK.spec, dt=WEEK.dt)
    for _ in range(int(round(HIDDEN_SECONDS / WEEK.dt))):
        rec = sim.step()
        if rec.collided:
            return ("collided", rec.t)
        if math.dist(rec.pose[:2], goal) < D_GOAL:
            return ("reached", rec.t)
    return ("not reached",)


def test_hidden_set_is_present_and_big_enough() -> None:
    data = load_hidden(7)
    assert data is not None and len(data["variants"]) >= 20
    # few goals need the wall following, are reached by both rules and decided for every kept version under
    # every kernel and nudge, most of them with the robot facing away from the trap's walls
    # (instructor_tools/hidden_week7.py); a seed still draws three start quarters, with a choice in each
    quarters = Counter(turn_quarter(v["turn"], v["of"]) for v in data["variants"])
    assert len(quarters) >= 3 and sorted(quarters.values())[-3] >= 2, quarters


@pytest.mark.slow
def test_every_hidden_goal_is_fair_from_nudged_starts(tmp_path) -> None:
    found = folders(tmp_path)
    nudges = ((0.0, 0.0), *NUDGES[-2:])  # the declared start and the largest nudges; the maker tried all
    unfair = [(v, nudge) for v in load_hidden(7)["variants"] for nudge in nudges if not fair(found, v, nudge)]
    assert unfair == []


@pytest.mark.slow
def test_reference_solution_reaches_every_hidden_goal() -> None:
    missed = []
    for v in load_hidden(7)["variants"]:
        got = outcome(ROOT / "solutions" / "week7", v)
        if got[0] != "reached" or abs(got[1] - v["reference_seconds"]) > 1e-6:
            missed.append((v, got))
    assert missed == []


@pytest.mark.slow
def test_the_stub_reaches_no_hidden_goal() -> None:
    stub = ROOT / "assignments" / "week7"
    reached = [v for v in load_hidden(7)["variants"] if outcome(stub, v)[0] == "reached"]
    assert reached == []
