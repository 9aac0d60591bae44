"""Week 4: solutions/week4 wanders the week-4 world for 60 s without touching anything, really moving,
and its sensor geometry reproduces the course's part-4.1 check. Wrong versions must fail."""

from __future__ import annotations

import math
from pathlib import Path

import mistakes
import pytest

from simiam.control import Pose2D, RobotView
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
WEEK = get_week(4)


def _folder(tmp_path: Path, mutant: str | None) -> Path:
    if mutant is None:
        return ROOT / "solutions/week4"
    return mistakes.build("submissions", mutant, tmp_path, 4)


def wander(folder: Path, dt: float) -> dict:
    """The week's 60 s avoid-obstacles scenario with the folder's own settings."""
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    sim = Simulator(load_world(WEEK.world), LocalBrain(sub, WEEK), WEEK.spec, dt=dt)
    trace = sim.run(WEEK.seconds)
    s = trace.steps
    n = len(trace)
    path = sum(math.hypot(s["x"][k + 1] - s["x"][k], s["y"][k + 1] - s["y"][k]) for k in range(n - 1))
    return {"collision": trace.collision, "t": s["t"][-1], "state": s["state"][-1], "path": path,
            "farthest": max(math.hypot(s["x"][k], s["y"][k]) for k in range(n))}


@pytest.mark.parametrize("dt", [0.033, 0.05])
def test_avoids_everything_for_60_s_and_really_moves(dt):
    r = wander(ROOT / "solutions/week4", dt)
    assert r["collision"] is None, r["collision"]
    assert r["t"] == pytest.approx(60.0, abs=dt)
    assert r["state"] == "avoid_obstacles"
    assert r["path"] > 5.0 and r["farthest"] > 0.5, r


def test_placeholder_avoid_obstacles_is_caught(tmp_path):
    assert wander(_folder(tmp_path, "week4_ao_placeholder"), 0.033)["collision"] is not None


def ir_points_error(folder: Path) -> tuple[float, float]:
    """The course's part 4.1: distances [d, 0.3, 0.3, d, 0.3] with d = 0.21 at the estimate
    (0.1, -0.1, -1.578); distances of points 1 and 4 from the course's expected world points."""
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    robot = RobotView(WEEK.spec, sub)
    ao = sub.module("avoid_obstacles").AvoidObstacles()
    _, wf = ao.apply_sensor_geometry(robot, [0.21, 0.3, 0.3, 0.21, 0.3], Pose2D(0.1, -0.1, -1.578))
    e1 = math.hypot(wf[0][0] - 0.3637, wf[1][0] - (-0.0545))
    e4 = math.hypot(wf[0][3] - (-0.0895), wf[1][3] - (-0.2932))
    return e1, e4


def test_sensor_geometry_matches_the_course_check():
    e1, e4 = ir_points_error(ROOT / "solutions/week4")
    assert e1 < 1e-3 and e4 < 1e-3, (e1, e4)


def test_transposed_rotation_is_caught(tmp_path):
    assert max(ir_points_error(_folder(tmp_path, "week4_transform_transposed"))) > 1e-2


def sensor_gains(folder: Path) -> list[float]:
    """Each sensor's weight in u_ao, measured from outside: move one sensor's IR point (a nearer raw value)
    and compare how far u_ao moves with how far the point moved (u_ao = sum g_i * (p_i - robot))."""
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    robot = RobotView(WEEK.spec, sub)
    inputs = sub.module("qb_supervisor").QBSupervisor().inputs()

    def u_ao_and_points(raw):
        robot.update({"ticks": [0, 0], "ir_raw": raw})
        ao = sub.module("avoid_obstacles").AvoidObstacles()
        ao.execute(robot, Pose2D(0.3, -0.2, 0.7), inputs, 0.033)
        return [float(c) for c in ao.u_ao[:2]], ao.ir_distances_wf

    u0, p0 = u_ao_and_points([133] * 5)
    gains = []
    for i in range(5):
        u, p = u_ao_and_points([400 if k == i else 133 for k in range(5)])
        moved = math.hypot(p[0][i] - p0[0][i], p[1][i] - p0[1][i])
        gains.append(math.hypot(u[0] - u0[0], u[1] - u0[1]) / moved)
    return gains


def test_sensor_gains_are_symmetric():
    """The manual: weights symmetric with respect to the left and right sides (sensors 1/5 and 2/4)."""
    g = sensor_gains(ROOT / "solutions/week4")
    assert g[0] == pytest.approx(g[4], rel=1e-9) and g[1] == pytest.approx(g[3], rel=1e-9), g
    assert min(g) > 0, g


def test_asymmetric_gains_are_caught(tmp_path):
    folder = mistakes.build("wrong", "week4_asymmetric_gains", tmp_path, 4)
    g = sensor_gains(folder)
    assert g[1] != pytest.approx(g[3], rel=1e-9), g


def test_free_space_steers_slightly_right():
    """With nothing in range u_ao points almost straight ahead, slightly right (the mounts' asymmetry)."""
    sub = load_submission(ROOT / "solutions/week4", WEEK)
    robot = RobotView(WEEK.spec, sub)
    robot.update({"ticks": [0, 0], "ir_raw": [133] * 5})
    ao = sub.module("avoid_obstacles").AvoidObstacles()
    ao.execute(robot, Pose2D(0.0, 0.0, 0.0), sub.module("qb_supervisor").QBSupervisor().inputs(), 0.033)
    heading = math.atan2(ao.u_ao[1], ao.u_ao[0])
    assert -0.2 < heading < 0.0, heading
