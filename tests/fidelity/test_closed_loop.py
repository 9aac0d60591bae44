"""Closed-loop GoToGoal runs of the solutions against the original's recordings.

- gotogoal_closed_loop.csv (dt 0.033) and gotogoal_closed_loop_dt0.05.csv: the sp14 code, i.e. the week-4
  supervisor in the go_to_goal state (odometry first, the dead-zone ensure_w), GoToGoal gains 4/0.01/0.01,
  the week-4 robot (130/30 rpm), in the week-3 world (walls only), v 0.2, d_stop 0.05.
- gotogoal_closed_loop_week3.csv: the week-3 code (odometry last, week-3 ensure_w, 80 rpm),
  gains 5/0.01/0.01.
Every goal present in a file is run; the true pose must match every recorded step to 1e-6 m, ticks
exactly, and the supervisor must be in the recorded state. A wrong step order must fail.
"""

from __future__ import annotations

import csv
import shutil
from collections import defaultdict
from pathlib import Path

import pytest

from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import week_config
from simiam.robot.quickbot import spec_for_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests/data/golden"
MUTANTS = ROOT / "tests/data/submissions"
TOL = 1e-6

# file -> (week of the code and robot, GoToGoal gains)
RUNS = {
    "gotogoal_closed_loop.csv": (4, {"Kp": 4, "Ki": 0.01, "Kd": 0.01}),
    "gotogoal_closed_loop_dt0.05.csv": (4, {"Kp": 4, "Ki": 0.01, "Kd": 0.01}),
    "gotogoal_closed_loop_week3.csv": (3, {"Kp": 5, "Ki": 0.01, "Kd": 0.01}),
}


def _goals(name: str) -> dict[str, list[dict]]:
    by_goal: dict[str, list[dict]] = defaultdict(list)
    with (GOLDEN / name).open() as f:
        for row in csv.DictReader(f):
            by_goal[row["goal_id"]].append(row)
    return by_goal


CASES = [(name, goal_id) for name in RUNS for goal_id in _goals(name)]


def replay(folder: Path, name: str, goal_id: str) -> list[str]:
    """Run the recorded scenario with the code in `folder`; return what differs from the recording."""
    week, gains = RUNS[name]
    rows = sorted(_goals(name)[goal_id], key=lambda r: int(r["step"]))
    dt = float(rows[1]["t"]) / int(rows[1]["step"])
    goal = (float(rows[0]["x_g"]), float(rows[0]["y_g"]))
    sub = load_submission(folder, week)
    assert sub.ok, sub.errors
    settings = {"v": 0.2, "d_stop": 0.05, "goal": goal, "state": "go_to_goal", "gains": {"go_to_goal": gains}}
    brain = LocalBrain(sub, week_config(week), settings)
    sim = Simulator(load_world("week3"), brain, spec_for_week(week), dt=dt, start=(0.0, 0.0, 0.0))
    problems = []
    for row in rows[1:]:
        rec = sim.step()
        assert rec.step == int(row["step"])
        err = max(abs(rec.pose[0] - float(row["x"])), abs(rec.pose[1] - float(row["y"])))
        if err > TOL:
            problems.append(f"step {rec.step}: true pose off by {err:.3g} m")
        recorded_ticks = [int(row["right_ticks"]), int(row["left_ticks"])]
        if list(rec.ticks) != recorded_ticks:
            problems.append(f"step {rec.step}: ticks {list(rec.ticks)}, recorded {recorded_ticks}")
        if rec.command["state"] != row["state"]:
            problems.append(f"step {rec.step}: state {rec.command['state']}, recorded {row['state']}")
        if problems:
            break
    return problems


@pytest.mark.parametrize(("name", "goal_id"), CASES)
def test_solutions_reproduce_the_recorded_run(name, goal_id):
    problems = replay(ROOT / f"solutions/week{RUNS[name][0]}", name, goal_id)
    assert not problems, f"{name} goal {goal_id}: {problems[0]}"


def test_every_file_has_cases():
    assert all(_goals(name) for name in RUNS)


def test_odometry_after_control_in_week4_is_caught(tmp_path):
    """The week-3 order (odometry last) in the week-4 supervisor does not reproduce the sp14 run."""
    folder = tmp_path / "mutant"
    shutil.copytree(ROOT / "solutions/week4", folder)
    shutil.copy(MUTANTS / "week4_odometry_last/qb_supervisor.py", folder / "qb_supervisor.py")
    name, goal_id = CASES[0]
    assert replay(folder, name, goal_id)
