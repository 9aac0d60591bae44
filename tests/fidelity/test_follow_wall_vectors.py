"""FollowWall of solutions/week6 against the original's (followwall_vectors.csv): one call per recorded input.

Every recorded case is run on a fresh controller (E = e_prev = 0) with the recorded raw IR values, estimate,
direction, d_fw, v and dt; p_1/p_2 (which sensors, and their points), u_fw_t, u_fw_tp, u_fw_p, the unit
vector toward the wall, u_fw, the heading, the error and w must match to 1e-9. The sp14 code kept that unit
vector in its u_fw_pp; the course's u_fw_pp is u_fw_p - d_fw * unit (zero at d_fw), checked against it.
A wrong sensor choice on ties must fail (shown once below). The shared copy holds only left cases; the
right side is proven by test_follow_wall_closed_loop.py.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import mistakes
import numpy as np

from simiam.control import Inputs, Pose2D, RobotView, norm
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week

ROOT = Path(__file__).resolve().parents[2]
WEEK6 = get_week(6)
GOLDEN = ROOT / "tests/data/golden/followwall_vectors.csv"
TOL = 1e-9


def _rows() -> list[dict[str, str]]:
    with GOLDEN.open(newline="") as f:
        return list(csv.DictReader(f))


def _pair(row: dict, name: str) -> tuple[float, float]:
    return float(row[f"{name}_x"]), float(row[f"{name}_y"])


def differences(folder: Path) -> list[str]:
    """Run every recorded input through the FollowWall in `folder`; what differs from the recording."""
    sub = load_submission(folder, WEEK6)
    assert sub.ok, sub.errors
    follow_wall = sub.module("follow_wall").FollowWall
    robot = RobotView(WEEK6.spec, sub)
    problems = []
    for row in _rows():
        case = f"case {row['case']} ({row['direction']}, d_fw {float(row['d_fw']):.4g})"
        robot.update({"ticks": [0, 0], "ir_raw": [int(row[f"ir_raw_{i}"]) for i in range(1, 6)]})
        estimate = Pose2D(float(row["x"]), float(row["y"]), float(row["theta"]))
        inputs = Inputs(v=float(row["v"]), direction=row["direction"], d_fw=float(row["d_fw"]))
        ctrl = follow_wall()
        v, w = ctrl.execute(robot, estimate, inputs, float(row["dt"]))

        wf = np.asarray(ctrl.ir_distances_wf)
        unit = np.asarray(ctrl.u_fw_p) / norm(ctrl.u_fw_p)
        got = {
            "p_1": tuple(ctrl.p_1), "p_2": tuple(ctrl.p_2),
            "u_fw_t": tuple(ctrl.u_fw_t), "u_fw_tp": tuple(ctrl.u_fw_tp), "u_fw_p": tuple(ctrl.u_fw_p),
            "u_fw_pp": tuple(unit), "u_fw": tuple(ctrl.u_fw),
        }
        for name, value in got.items():
            want = _pair(row, name)
            if max(abs(value[0] - want[0]), abs(value[1] - want[1])) > TOL:
                problems.append(f"{case}: {name} {value}, recorded {want}")
        pp = np.asarray(ctrl.u_fw_pp)
        want_pp = np.asarray(_pair(row, "u_fw_p")) - float(row["d_fw"]) * np.asarray(_pair(row, "u_fw_pp"))
        if np.max(np.abs(pp - want_pp)) > TOL:
            problems.append(f"{case}: u_fw_pp {tuple(pp)}, recorded u_fw_p - d_fw * unit = {tuple(want_pp)}")
        for k, name in ((1, "p_1"), (2, "p_2")):
            sensor = int(row[f"p{k}_sensor"]) - 1
            if tuple(wf[0:2, sensor]) != got[name]:
                problems.append(f"{case}: {name} is not the point of sensor {sensor} (the manual's "
                                f"{sensor + 1}), as recorded")
        for name, value in (("heading", ctrl.theta_g), ("e_k", ctrl.e_k_1), ("w", w), ("v_out", v)):
            if not math.isclose(value, float(row[name]), rel_tol=0, abs_tol=TOL):
                problems.append(f"{case}: {name} {value!r}, recorded {row[name]}")
    return problems


def test_solution_reproduces_every_recorded_input():
    problems = differences(ROOT / "solutions/week6")
    assert not problems, f"{len(problems)} differences, first: {problems[0]}"


def test_recorded_choices_include_ties():
    """The shared copy holds the odd (left) cases; the right side is proven by the closed loops.
    In at least ten cases the second-closest left sensor is a tie, which only the stable sort decides."""
    tied = 0
    for r in _rows():
        d = sorted(float(r[f"ir_dist_{i}"]) for i in (1, 2, 3))
        tied += d[1] == d[2] or d[0] == d[1]
    assert tied >= 10


def test_a_wrong_sensor_choice_on_ties_is_caught(tmp_path):
    assert differences(mistakes.build("wrong", "week6_ties_prefer_last", tmp_path, 6))
