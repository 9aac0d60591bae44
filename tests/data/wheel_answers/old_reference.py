# WRONG VERSION kept for tests/packaging/test_answer_search.py: grader/reference.py as it shipped before issue 11 was closed (odometry, ensure_w, the transformation matrix and theta_g in other wording)
"""Trusted reference maths the checks compare student answers against.

Runs only in the grading process. The kinematics come from the trusted simulator (`simiam.robot`); the
rest is the course's formulas written out once (reference/original-simulator.md sections 2-5).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from simiam.robot import dynamics
from simiam.robot.ir_sensor import distance_to_raw, ir_voltage
from simiam.robot.quickbot import RobotSpec, limit_speeds
from simiam.robot.wheel_encoder import WheelEncoder

# The manual's look-up table (Figure 2b): distance (m), voltage (V).
# ADC = 1000*V/3 from week 3, 500*V in week 2.
IR_TABLE: tuple[tuple[float, float], ...] = (
    (0.04, 2.750),
    (0.05, 2.350),
    (0.06, 2.050),
    (0.07, 1.750),
    (0.08, 1.550),
    (0.09, 1.400),
    (0.10, 1.275),
    (0.12, 1.075),
    (0.14, 0.925),
    (0.16, 0.805),
    (0.18, 0.725),
    (0.20, 0.650),
    (0.25, 0.500),
    (0.30, 0.400),
)


def uni_to_diff(spec: RobotSpec, v: float, w: float) -> tuple[float, float]:
    """(v, w) -> (vel_r, vel_l) in rad/s."""
    return dynamics.uni_to_diff(spec.wheel_radius, spec.wheel_base_length, v, w)


def diff_to_uni(spec: RobotSpec, vel_r: float, vel_l: float) -> tuple[float, float]:
    """(vel_r, vel_l) -> (v, w)."""
    return dynamics.diff_to_uni(spec.wheel_radius, spec.wheel_base_length, vel_r, vel_l)


def wrap(angle: float) -> float:
    """The course's wrap into [-pi, pi]: atan2(sin a, cos a)."""
    return math.atan2(math.sin(angle), math.cos(angle))


def angle_diff(a: float, b: float) -> float:
    """|a - b| as angles (0 .. pi), so 3.14 and -3.14 are close."""
    return abs(wrap(a - b))


def theta_g(x: float, y: float, x_g: float, y_g: float) -> float:
    """The heading from (x, y) to the goal."""
    return math.atan2(y_g - y, x_g - x)


def m_per_tick(spec: RobotSpec) -> float:
    """Metres a wheel rolls per encoder tick."""
    return 2 * math.pi * spec.wheel_radius / spec.ticks_per_rev


def odometry_step(
    spec: RobotSpec, pose: Sequence[float], d_ticks_r: int, d_ticks_l: int
) -> tuple[float, float, float]:
    """The course's odometry update (heading of the old pose, theta not wrapped)."""
    x, y, theta = pose
    d_r = d_ticks_r * m_per_tick(spec)
    d_l = d_ticks_l * m_per_tick(spec)
    d_c = (d_r + d_l) / 2
    phi = (d_r - d_l) / spec.wheel_base_length
    return x + d_c * math.cos(theta), y + d_c * math.sin(theta), theta + phi


def drive(
    spec: RobotSpec,
    wheels: list[tuple[float, float]],
    dt: float,
    start: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> tuple[list[tuple[int, int]], list[tuple]]:
    """Drive open loop with the requested wheel speeds per step (the robot's limits apply).

    Returns the cumulative encoder ticks [right, left] and the true pose after each step.
    """
    right, left = WheelEncoder(spec.ticks_per_rev), WheelEncoder(spec.ticks_per_rev)
    pose = start
    ticks, poses = [], []
    for vel_r, vel_l in wheels:
        vel_r, vel_l = limit_speeds(vel_r, vel_l, spec.max_vel, spec.min_vel)
        pose = dynamics.move(*pose, vel_r, vel_l, spec.wheel_radius, spec.wheel_base_length, dt)
        right.update(vel_r, dt)
        left.update(vel_l, dt)
        ticks.append((right.ticks, left.ticks))
        poses.append(pose)
    return ticks, poses


def go_to_angle_run(
    spec: RobotSpec, v: float, theta_d: float, steps: int, dt: float, kp: float = 1.0
) -> tuple[list[tuple[int, int]], list[tuple]]:
    """The course's week-2 odometry test: GoToAngle with the reference uni_to_diff and odometry, week-2 order.

    Each step moves the robot with last step's wheels, then the controller sets new wheels from the
    estimate, then odometry reads the new ticks. Returns the ticks and true poses after each step.
    """
    right, left = WheelEncoder(spec.ticks_per_rev), WheelEncoder(spec.ticks_per_rev)
    pose = est = (0.0, 0.0, 0.0)
    wheels = (0.0, 0.0)
    prev = (0, 0)
    ticks, poses = [], []
    for _ in range(steps):
        pose = dynamics.move(*pose, *wheels, spec.wheel_radius, spec.wheel_base_length, dt)
        right.update(wheels[0], dt)
        left.update(wheels[1], dt)
        w = kp * wrap(theta_d - est[2])
        wheels = limit_speeds(*uni_to_diff(spec, v, w), spec.max_vel, spec.min_vel)
        est = odometry_step(spec, est, right.ticks - prev[0], left.ticks - prev[1])
        prev = (right.ticks, left.ticks)
        ticks.append(prev)
        poses.append(pose)
    return ticks, poses


def ensure_w_week3(spec: RobotSpec, v: float, w: float) -> tuple[float, float]:
    """The week-3 reference `ensure_w`: keep w, give up v, then the robot's limits. Returns applied wheels."""
    _, w_max_v0 = diff_to_uni(spec, spec.max_vel, -spec.max_vel)
    v_max_w0, _ = diff_to_uni(spec, spec.max_vel, spec.max_vel)
    w = max(min(w, w_max_v0), -w_max_v0)
    v = max(min(v, v_max_w0), -v_max_w0)
    vel_r, vel_l = uni_to_diff(spec, v, w)
    hi, lo = max(vel_r, vel_l), min(vel_r, vel_l)
    if hi > spec.max_vel:
        vel_r, vel_l = vel_r - (hi - spec.max_vel), vel_l - (hi - spec.max_vel)
    elif lo < -spec.max_vel:
        vel_r, vel_l = vel_r + (-spec.max_vel - lo), vel_l + (-spec.max_vel - lo)
    return limit_speeds(vel_r, vel_l, spec.max_vel, spec.min_vel)


def max_turn_rate(spec: RobotSpec) -> float:
    """The largest |w| the robot can turn with (on the spot, both wheels at max_vel)."""
    return diff_to_uni(spec, spec.max_vel, -spec.max_vel)[1]


def transformation_matrix(x: float, y: float, theta: float) -> list[list[float]]:
    """T(x, y, theta): rotate by theta, then translate by (x, y)."""
    c, s = math.cos(theta), math.sin(theta)
    return [[c, -s, x], [s, c, y], [0.0, 0.0, 1.0]]


def apply(t: list[list[float]], point: tuple[float, float]) -> tuple[float, float]:
    """T * [px, py, 1], the (x, y) part."""
    px, py = point
    return t[0][0] * px + t[0][1] * py + t[0][2], t[1][0] * px + t[1][1] * py + t[1][2]


def sensor_points(
    spec: RobotSpec, distances: list[float], pose: Sequence[float]
) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """Each IR distance as a point in the robot frame (via the mount) and the world frame (via the pose)."""
    robot_frame = [
        apply(transformation_matrix(*mount), (d, 0.0))
        for mount, d in zip(spec.ir_mounts, distances, strict=False)
    ]
    pose_t = transformation_matrix(*pose)
    return robot_frame, [apply(pose_t, p) for p in robot_frame]


def ir_raw(spec: RobotSpec, distance: float) -> int:
    """The raw ADC value the simulator reports for an obstacle at `distance` (this week's divider)."""
    return distance_to_raw(distance, spec.ir_mode)


def ir_divider(spec: RobotSpec) -> float:
    """Raw units per volt: 500 in week 2 (the manual's week-2 divider), 1000/3 from week 3."""
    return 500.0 if spec.ir_mode == "week2" else 1000.0 / 3.0


__all__ = [
    "IR_TABLE",
    "angle_diff",
    "apply",
    "diff_to_uni",
    "drive",
    "ensure_w_week3",
    "go_to_angle_run",
    "ir_divider",
    "ir_raw",
    "ir_voltage",
    "m_per_tick",
    "max_turn_rate",
    "odometry_step",
    "sensor_points",
    "theta_g",
    "transformation_matrix",
    "uni_to_diff",
    "wrap",
]
