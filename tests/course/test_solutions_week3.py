"""Week 3: solutions/week3 drives to the goal, stops within d_stop, and its gains meet the manual's target.

Settle time and overshoot are measured as the course's grader did (part 3.2): the reference r = theta_g
and y = the wrapped estimated heading the controller used, per step; settle = (k - 20) * dt with k the
first index ending 21 consecutive samples with |(r - y) / r| < 0.1; overshoot = |r - y| / |r| at the
sample where y goes furthest in the direction of r. Target: settle <= 3 s, overshoot <= 10 %.
Wrong versions in tests/data/submissions/ must fail.
"""

from __future__ import annotations

import math
from pathlib import Path

import mistakes
import pytest

from simiam.control import Inputs, Pose2D
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
WEEK = get_week(3)
GOALS = [(0.0, -1.0), (-1.0, 1.0)]  # the manual's example and the week's default goal


def _folder(tmp_path: Path, mutant: str | None) -> Path:
    if mutant is None:
        return ROOT / "solutions/week3"
    return mistakes.build("submissions", mutant, tmp_path, 3)


def _run(folder: Path, goal, dt: float, seconds: float):
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    brain = LocalBrain(sub, WEEK, {"goal": goal, "v": 0.2, "d_stop": 0.05})
    sim = Simulator(load_world(WEEK.world), brain, WEEK.spec, dt=dt)
    return sim.run(seconds)


def arrival(folder: Path, goal, dt: float) -> dict:
    """Run the week's 30 s scenario: did it stop, how far from the goal, did it collide."""
    s = (trace := _run(folder, goal, dt, WEEK.seconds)).steps
    stops = [k for k, st in enumerate(s["state"]) if st == "stop"]
    after = stops[0] if stops else len(trace) - 1
    return {"stopped": bool(stops), "collision": trace.collision,
            "distance": math.hypot(s["x"][-1] - goal[0], s["y"][-1] - goal[1]),
            "drift_after_stop": math.hypot(s["x"][-1] - s["x"][after], s["y"][-1] - s["y"][after])}


def settle_and_overshoot(folder: Path, goal, dt: float) -> tuple[float, float]:
    """The course's part-3.2 measure over up to 15 s, until the robot stops or collides."""
    s = _run(folder, goal, dt, 15.0).steps
    ys, rs = [], []
    theta_used = 0.0  # week 3 updates odometry last: the controller of step k saw the estimate of step k-1
    for k in range(1, len(s["t"])):
        if s["state"][k] != "go_to_goal" or s["theta_g"][k] is None:
            break
        ys.append(math.atan2(math.sin(theta_used), math.cos(theta_used)))
        rs.append(s["theta_g"][k])
        theta_used = s["theta_est"][k]
    settle, run = -dt, 0
    for k, (y, r) in enumerate(zip(ys, rs, strict=True)):
        run = run + 1 if abs((r - y) / r) < 0.1 else 0
        if run == 21:
            settle = (k - 20) * dt
            break
    i = (max if rs[0] > 0 else min)(range(len(ys)), key=lambda j: ys[j])
    return settle, abs((rs[i] - ys[i]) / rs[i])


@pytest.mark.parametrize("goal", GOALS + [(1.0, 1.0)])
@pytest.mark.parametrize("dt", [0.033, 0.05])
def test_reaches_the_goal_and_stops(goal, dt):
    r = arrival(ROOT / "solutions/week3", goal, dt)
    assert r["collision"] is None
    assert r["stopped"] and r["distance"] < 0.05, r
    assert r["drift_after_stop"] == 0.0


@pytest.mark.parametrize("goal", GOALS)
@pytest.mark.parametrize("dt", [0.033, 0.05])
def test_gains_settle_fast_without_overshoot(goal, dt):
    settle, overshoot = settle_and_overshoot(ROOT / "solutions/week3", goal, dt)
    assert 0 <= settle <= 3.0, f"settle {settle:.3f} s"
    assert overshoot <= 0.10, f"overshoot {overshoot:.1%}"


def test_placeholder_gains_are_caught(tmp_path):
    r = arrival(_folder(tmp_path, "week3_gains_placeholder"), GOALS[1], 0.033)
    assert r["collision"] is not None or not r["stopped"]


def test_overshooting_gains_are_caught(tmp_path):
    _, overshoot = settle_and_overshoot(_folder(tmp_path, "week3_gains_overshoot"), GOALS[0], 0.05)
    assert overshoot > 0.10


def heading_error_across_pi(folder: Path) -> float:
    """The error GoToGoal keeps (e_k_1) when the estimate heads at 3.0 rad and the goal lies at -3.0 rad:
    0.283 rad (a small left turn) once wrapped into [-pi, pi], -6.0 if not."""
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    ctrl = sub.module("go_to_goal").GoToGoal()
    inputs = Inputs(v=0.2, x_g=math.cos(-3.0), y_g=math.sin(-3.0))
    ctrl.execute(None, Pose2D(0.0, 0.0, 3.0), inputs, 0.033)
    return ctrl.e_k_1


def test_heading_error_is_wrapped():
    assert heading_error_across_pi(ROOT / "solutions/week3") == pytest.approx(2 * math.pi - 6.0, abs=1e-12)


def test_unwrapped_heading_error_is_caught(tmp_path):
    folder = mistakes.build("wrong", "week3_no_wrap", tmp_path, 3)
    assert heading_error_across_pi(folder) == pytest.approx(-6.0, abs=1e-12)
