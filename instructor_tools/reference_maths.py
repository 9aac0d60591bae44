"""Reference implementations of student blocks, for the instructor's tooling only (never in the wheel).

`uni_to_diff` in the original's operation order (the reference brains drive with it; the fidelity tests
hold it to the recordings bit for bit), the course's odometry update, the week-3 `ensure_w`, and the
course's week-2 odometry test run. `python -m instructor_tools.expected` uses them to precompute the few
expected values the grader's checks read as data (grader/checks/expected/), and tests/grader/
test_reference_maths.py holds grader.reference's properties to them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from simiam.robot import dynamics
from simiam.robot.quickbot import RobotSpec, limit_speeds
from simiam.robot.wheel_encoder import WheelEncoder


def uni_to_diff(R: float, L: float, v: float, w: float) -> tuple[float, float]:
    """Unicycle (v, w) -> wheel speeds (vel_r, vel_l), in the original's operation order."""
    vel_r = (2 * v + w * L) / (2 * R)
    vel_l = (2 * v - w * L) / (2 * R)
    return vel_r, vel_l


def odometry_step(
    spec: RobotSpec, pose: Sequence[float], d_ticks_r: int, d_ticks_l: int
) -> tuple[float, float, float]:
    """The course's odometry update (heading of the old pose, theta not wrapped)."""
    x, y, theta = pose
    per_tick = 2 * math.pi * spec.wheel_radius / spec.ticks_per_rev
    d_r, d_l = d_ticks_r * per_tick, d_ticks_l * per_tick
    d_c = (d_r + d_l) / 2
    phi = (d_r - d_l) / spec.wheel_base_length
    return x + d_c * math.cos(theta), y + d_c * math.sin(theta), theta + phi


def ensure_w_week3(spec: RobotSpec, v: float, w: float) -> tuple[float, float]:
    """The week-3 reference `ensure_w`: keep w, give up v, then the robot's limits. Returns applied wheels."""
    R, L = spec.wheel_radius, spec.wheel_base_length
    _, w_max_v0 = dynamics.diff_to_uni(R, L, spec.max_vel, -spec.max_vel)
    v_max_w0, _ = dynamics.diff_to_uni(R, L, spec.max_vel, spec.max_vel)
    w = max(min(w, w_max_v0), -w_max_v0)
    v = max(min(v, v_max_w0), -v_max_w0)
    vel_r, vel_l = uni_to_diff(R, L, v, w)
    hi, lo = max(vel_r, vel_l), min(vel_r, vel_l)
    if hi > spec.max_vel:
        vel_r, vel_l = vel_r - (hi - spec.max_vel), vel_l - (hi - spec.max_vel)
    elif lo < -spec.max_vel:
        vel_r, vel_l = vel_r + (-spec.max_vel - lo), vel_l + (-spec.max_vel - lo)
    return limit_speeds(vel_r, vel_l, spec.max_vel, spec.min_vel)


def go_to_angle_run(
    spec: RobotSpec, v: float, theta_d: float, steps: int, dt: float, kp: float = 1.0
) -> tuple[list[tuple[int, int]], list[tuple], list[tuple]]:
    """The course's week-2 odometry test: GoToAngle with the reference uni_to_diff and odometry, week-2 order.

    Each step moves the robot with last step's wheels, then the controller sets new wheels from the
    estimate, then odometry reads the new ticks. Returns the ticks, true poses and estimates after each step.
    """
    R, L = spec.wheel_radius, spec.wheel_base_length
    right, left = WheelEncoder(spec.ticks_per_rev), WheelEncoder(spec.ticks_per_rev)
    pose = est = (0.0, 0.0, 0.0)
    wheels = (0.0, 0.0)
    prev = (0, 0)
    ticks, poses, estimates = [], [], []
    for _ in range(steps):
        pose = dynamics.move(*pose, *wheels, R, L, dt)
        right.update(wheels[0], dt)
        left.update(wheels[1], dt)
        w = kp * math.atan2(math.sin(theta_d - est[2]), math.cos(theta_d - est[2]))
        wheels = limit_speeds(*uni_to_diff(R, L, v, w), spec.max_vel, spec.min_vel)
        est = odometry_step(spec, est, right.ticks - prev[0], left.ticks - prev[1])
        prev = (right.ticks, left.ticks)
        ticks.append(prev)
        poses.append(pose)
        estimates.append(est)
    return ticks, poses, estimates
