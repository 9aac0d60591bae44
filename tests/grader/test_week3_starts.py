"""Week 3's runs from a start away from the origin (issue 31): before them every run started at (0, 0, 0),
where a theta_g that ignores the robot's position (atan2(y_g, x_g), a real student's: kept as
tests/data/wrong/week3_theta_g_origin_bearing.patch) is right, and it collected every behaviour point.

The draws are vetted as the other hidden draws are (issue 20: right and wrong apart by a margin): over many
seeds, the reference solution and a correct alternative with other gains reach every drawn goal from its
start with ARRIVAL_SPARE seconds and CLEARANCE_SPARE metres to spare, and the origin's bearing misses each
goal by MISS_BY or more."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from wrong_submissions import build

from grader.checks.week3 import MISS_BY, ROBOT_D_STOP, START_MIN, drawable_from, seeded_start_and_goal
from grader.scenarios import min_clearance
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import World, load_world

ROOT = Path(__file__).resolve().parents[2]
SEEDS = [2014, *range(12)]
ARRIVAL_SPARE = 10.0   # s under the 30 s limit
CLEARANCE_SPARE = 0.1  # m from every wall


def _draws() -> list[tuple[tuple[float, float, float], tuple[float, float]]]:
    return [seeded_start_and_goal(seed, salt) for seed in SEEDS for salt in ("visible", "hidden")]


def test_every_draw_starts_away_and_the_origins_bearing_misses_its_goal() -> None:
    for start, goal in _draws():
        assert drawable_from(start, goal)
        assert math.hypot(start[0], start[1]) >= START_MIN
        b = math.atan2(goal[1], goal[0])
        dx, dy = goal[0] - start[0], goal[1] - start[1]
        assert dx * math.cos(b) + dy * math.sin(b) < 0 or abs(dy * math.cos(b) - dx * math.sin(b)) >= MISS_BY
    assert not drawable_from((0.0, 0.0, 0.0), (1.0, 0.5))  # the origin itself is never drawn


@pytest.mark.parametrize("version", ["solutions", "good_week3_other_gains"])
def test_correct_controllers_reach_every_draw_with_a_margin(version: str, tmp_path) -> None:
    week = get_week(3)
    folder = ROOT / "solutions" / "week3" if version == "solutions" else build(version, tmp_path)
    sub = load_submission(folder, week)
    world = load_world(week.world)
    late = []
    for start, goal in _draws():
        settings = week.settings.with_changes(goal=list(goal), d_stop=ROBOT_D_STOP, state="go_to_goal")
        brain = LocalBrain(sub, week, settings.as_dict(), start=start)
        sim = Simulator(World(world.name, world.obstacles, [start], goal, world.source), brain, week.spec,
                        dt=week.dt, start=start)
        trace = sim.run(week.seconds, until=lambda rec, g=goal: math.dist(rec.pose[:2], g) < 0.05)
        arrived = trace.ending.t if trace.ending.reason.name == "UNTIL" else None
        gap = min_clearance(trace, world, week.spec)
        if arrived is None or arrived > week.seconds - ARRIVAL_SPARE or gap is None or gap < CLEARANCE_SPARE:
            late.append((start, goal, arrived, gap))
    assert late == []
