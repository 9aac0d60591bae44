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
import math
from collections import defaultdict
from pathlib import Path

import mistakes
import pytest

from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week, spec_for_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests/data/golden"
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
    brain = LocalBrain(sub, get_week(week), settings)
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
    folder = mistakes.build("submissions", "week4_odometry_last", tmp_path, 4)
    name, goal_id = CASES[0]
    assert replay(folder, name, goal_id)


# The golden files here hold goal 1 of each run; the full recordings also have goals (-1, 1) and (0, -1)
# (../shared/golden/README.md), kept back. Until they are dropped in, the solutions are run on those goals
# against the independent reference brain (instructor_tools.reference_brains), which reproduces every
# recorded goal:
# both must command the very same wheel speeds at every step (goal 2 zeroes a wheel at step 16 by one ulp).
BRAIN_OPTIONS = {
    "gotogoal_closed_loop.csv": (0.033, {}),
    "gotogoal_closed_loop_dt0.05.csv": (0.05, {}),
    "gotogoal_closed_loop_week3.csv": (0.033, {"gains": (5.0, 0.01, 0.01), "ensure": "week3",
                                               "odometry_last": True}),
}


def disagreement(folder: Path, name: str, goal: tuple[float, float]) -> str | None:
    """First step where the folder's code and the reference brain command different wheel speeds."""
    from instructor_tools.reference_brains import GoToGoalBrain

    week, gains = RUNS[name]
    dt, options = BRAIN_OPTIONS[name]
    sub = load_submission(folder, week)
    assert sub.ok, sub.errors
    settings = {"v": 0.2, "d_stop": 0.05, "goal": goal, "state": "go_to_goal", "gains": {"go_to_goal": gains}}
    spec = spec_for_week(week)
    ours = Simulator(load_world("week3"), LocalBrain(sub, get_week(week), settings), spec, dt=dt)
    reference = GoToGoalBrain(spec, goal, v=0.2, d_stop=0.05, **options)
    ref = Simulator(load_world("week3"), reference, spec, dt=dt)
    for _ in range(int(round(10.0 / dt))):
        a, b = ours.step(), ref.step()
        if (a.vel_r, a.vel_l, a.command["state"]) != (b.vel_r, b.vel_l, b.command["state"]):
            return f"step {a.step}: ({a.vel_r!r}, {a.vel_l!r}) vs reference ({b.vel_r!r}, {b.vel_l!r})"
    return None


@pytest.mark.parametrize("goal", [(1.0, 1.0), (-1.0, 1.0), (0.0, -1.0)])
@pytest.mark.parametrize("name", sorted(RUNS))
def test_solutions_agree_with_the_reference_brain_on_every_recorded_goal(name, goal):
    assert disagreement(ROOT / f"solutions/week{RUNS[name][0]}", name, goal) is None


def test_reference_cross_check_catches_a_reordered_diff_to_uni(tmp_path):
    """R*(r-l)/L instead of R/L*(r-l): one ulp in ensure_w's round trip, a different dead-zone decision."""
    folder = mistakes.build("submissions", "week4_diff_to_uni_reordered", tmp_path, 4)
    goals = [(1.0, 1.0), (-1.0, 1.0), (0.0, -1.0)]
    assert any(disagreement(folder, "gotogoal_closed_loop.csv", g) for g in goals)


# What ../shared/golden/README.md states about every recorded goal, held-back ones included: when the
# supervisor switched to stop (s) and how far from the goal the robot ended (m, 3 decimals).
STOPS = {
    "gotogoal_closed_loop.csv": ((6.897, 0.046), (7.392, 0.044), (4.983, 0.038)),
    "gotogoal_closed_loop_dt0.05.csv": ((6.95, None), (7.45, None), (5.00, None)),
    "gotogoal_closed_loop_week3.csv": ((6.996, None), (7.293, None), (5.082, None)),
}


def stop_time_and_distance(folder: Path, name: str, goal: tuple[float, float]) -> tuple[float, float]:
    week, gains = RUNS[name]
    dt = BRAIN_OPTIONS[name][0]
    sub = load_submission(folder, week)
    assert sub.ok, sub.errors
    settings = {"v": 0.2, "d_stop": 0.05, "goal": goal, "state": "go_to_goal", "gains": {"go_to_goal": gains}}
    sim = Simulator(load_world("week3"), LocalBrain(sub, get_week(week), settings), spec_for_week(week),
                    dt=dt)
    trace = sim.run(10.0, until=lambda rec: rec.command["state"] == "stop")
    x, y, _ = sim.pose
    return trace.steps["t"][-1], math.hypot(x - goal[0], y - goal[1])


@pytest.mark.parametrize("name", sorted(STOPS))
def test_solutions_stop_when_the_recordings_did(name):
    for goal, (t_stop, distance) in zip([(1.0, 1.0), (-1.0, 1.0), (0.0, -1.0)], STOPS[name], strict=True):
        t, d = stop_time_and_distance(ROOT / f"solutions/week{RUNS[name][0]}", name, goal)
        assert t == pytest.approx(t_stop, abs=1e-9), (goal, t)
        if distance is not None:
            assert round(d, 3) == distance, (goal, d)
