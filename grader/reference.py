"""The one module of trusted reference maths the checks judge student answers with (issue 14).

Runs only in the grading process, and ships in the student's wheel, so it holds no answer of any student
block (issue 11; tests/packaging/test_answer_search.py searches it for every block of solutions/). What it
holds instead:

- what the course gives every student anyway: the manual's IR table and dividers, the provided
  `diff_to_uni` and `m_per_tick`, the provided wrap of go_to_angle.py;
- the trusted simulator's own models: wheels and encoders driven open loop (`drive`), and where the
  simulator places a point given a pose (`place`, `matrix_of`, `sensor_points`), read off its physics;
- what a correct answer must satisfy, stated as a property rather than computed the student's way:
  `ensure_w_command` (the (v, w) the motors can give that keeps w and gives up the least v),
  `points_at` (a heading points along a vector), `bearing` (the direction of a vector, for the scenario
  metrics and the messages).

Where no property pins an answer, the check reads expected values that instructor tooling precomputed
(grader/checks/expected/, drift-tested against instructor_tools/reference_maths.py).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from simiam.physics.transform import transform_fast
from simiam.robot import dynamics
from simiam.robot.ir_sensor import distance_to_raw, ir_voltage
from simiam.robot.quickbot import RobotSpec, limit_speeds
from simiam.robot.rounding import round_half_away
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


def diff_to_uni(spec: RobotSpec, vel_r: float, vel_l: float) -> tuple[float, float]:
    """(vel_r, vel_l) -> (v, w): the provided diff_to_uni (the simulator's own, in the original's order)."""
    return dynamics.diff_to_uni(spec.wheel_radius, spec.wheel_base_length, vel_r, vel_l)


def wrap(angle: float) -> float:
    """The course's wrap into [-pi, pi] (provided in go_to_angle.py): atan2(sin a, cos a)."""
    return math.atan2(math.sin(angle), math.cos(angle))


def angle_diff(a: float, b: float) -> float:
    """|a - b| as angles (0 .. pi), so 3.14 and -3.14 are close."""
    return abs(wrap(a - b))


def bearing(dx: float, dy: float) -> float:
    """The direction of the vector (dx, dy), in [-pi, pi]."""
    return math.atan2(dy, dx)


def points_at(heading: float, dx: float, dy: float) -> float:
    """How far (rad, 0 .. pi) the unit vector of `heading` is from pointing along (dx, dy): the angle
    between the two vectors, from their cross and dot products."""
    c, s = math.cos(heading), math.sin(heading)
    return abs(math.atan2(c * dy - s * dx, c * dx + s * dy))


def m_per_tick(spec: RobotSpec) -> float:
    """Metres a wheel rolls per encoder tick (provided in qb_supervisor.py)."""
    return 2 * math.pi * spec.wheel_radius / spec.ticks_per_rev


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


def max_turn_rate(spec: RobotSpec) -> float:
    """The largest |w| the robot can turn with (on the spot, both wheels at max_vel)."""
    return diff_to_uni(spec, spec.max_vel, -spec.max_vel)[1]


def ensure_w_command(spec: RobotSpec, v: float, w: float) -> tuple[float, float]:
    """The (v, w) a correct ensure_w drives with, by the properties the week-3 handout states.

    w is kept, cut only to the largest turn rate the motors allow; the same shift on both wheels changes v
    alone, so v is the requested v moved the least that puts both wheels within max_vel: with turn rate w
    the faster wheel runs |w| * L / (2 * R) above the mean, so the mean may reach R * max_vel - |w| * L / 2
    and no further (both ways).
    """
    w_max = max_turn_rate(spec)
    kept_w = max(min(w, w_max), -w_max)
    top = max(0.0, spec.wheel_radius * spec.max_vel - abs(kept_w) * spec.wheel_base_length / 2)
    return max(min(v, top), -top), kept_w


def place(pose: Sequence[float], point: tuple[float, float]) -> tuple[float, float]:
    """Where the simulator puts `point` (given in the frame of `pose`) in the outer frame."""
    xs, ys = transform_fast((pose[0], pose[1], pose[2]), [point])
    return xs[0], ys[0]


def placed(pose: Sequence[float], points: Sequence[tuple[float, float]]) -> list[tuple[float, float]]:
    """Where the simulator puts many points given in the frame of `pose` (its own transform)."""
    xs, ys = transform_fast((pose[0], pose[1], pose[2]), points)
    return list(zip(xs, ys, strict=True))


def travel(spec: RobotSpec, d_ticks_r: int, d_ticks_l: int) -> tuple[float, float]:
    """How far the robot's centre rolls and how much it turns (rad) while the encoders count these ticks:
    the mean and the difference over L of the wheels' arcs (the simulator's drive: each wheel rolls
    m_per_tick per tick, and the turn of an arc is (d_r - d_l)/L)."""
    d_r, d_l = d_ticks_r * m_per_tick(spec), d_ticks_l * m_per_tick(spec)
    return (d_r + d_l) / 2, (d_r - d_l) / spec.wheel_base_length


def matrix_of(x: float, y: float, theta: float) -> list[list[float]]:
    """The 3x3 matrix of the simulator's placement at pose (x, y, theta), read off where it puts the unit
    vectors (rotation alone) and the origin (translation alone): columns T e1, T e2, T 0."""
    (c1, c2), (s1, s2) = transform_fast((0.0, 0.0, theta), [(1.0, 0.0), (0.0, 1.0)])
    (tx,), (ty,) = transform_fast((x, y, 0.0), [(0.0, 0.0)])
    return [[c1, c2, tx], [s1, s2, ty], [0.0, 0.0, 1.0]]


def sensor_points(
    spec: RobotSpec, distances: list[float], pose: Sequence[float]
) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """Each IR distance as the simulator places it: in the robot frame (via the mount) and in the world
    (via the pose)."""
    robot_frame = [place(mount, (d, 0.0)) for mount, d in zip(spec.ir_mounts, distances, strict=False)]
    return robot_frame, [place(pose, p) for p in robot_frame]


def ir_raw(spec: RobotSpec, distance: float) -> int:
    """The raw ADC value the simulator reports for an obstacle at `distance` (this week's divider)."""
    return distance_to_raw(distance, spec.ir_mode)


def ir_divider(spec: RobotSpec) -> float:
    """Raw units per volt: 500 in week 2 (the manual's week-2 divider), 1000/3 from week 3."""
    return 500.0 if spec.ir_mode == "week2" else 1000.0 / 3.0


def table_raw(spec: RobotSpec, volts: float) -> int:
    """The raw value of a table voltage through this week's divider, rounded as the simulator's ADC rounds
    (MATLAB's round, half away from zero, exact)."""
    return round_half_away(ir_divider(spec) * volts)


__all__ = [
    "IR_TABLE",
    "angle_diff",
    "bearing",
    "diff_to_uni",
    "drive",
    "ensure_w_command",
    "ir_divider",
    "ir_raw",
    "ir_voltage",
    "limit_speeds",
    "m_per_tick",
    "matrix_of",
    "max_turn_rate",
    "place",
    "placed",
    "points_at",
    "sensor_points",
    "table_raw",
    "travel",
    "wrap",
]


def dot(u: Sequence[float], v: Sequence[float]) -> float:
    """u . v summed left to right in plain float arithmetic: the same last bit on every CPU (numpy's `@`
    hands it to the BLAS kernel the CPU picks, some of which fuse the multiply and the add)."""
    total = 0.0
    for a, b in zip(u, v, strict=True):
        total += a * b
    return total


def least_squares(rows: Sequence[Sequence[float]], rhs: Sequence[float]) -> list[float]:
    """x minimising |A x - b| for A = rows, b = rhs, solved exactly in rationals (the normal equations
    AᵀA x = Aᵀb by Gauss-Jordan elimination), then rounded once: no BLAS, so every CPU finds the same x.
    Where AᵀA is singular the free unknowns are 0 (a least-squares solution, not the least-norm one)."""
    from fractions import Fraction

    a = [[Fraction(value) for value in row] for row in rows]
    b = [Fraction(value) for value in rhs]
    n = len(a[0]) if a else 0
    normal = [[sum((row[i] * row[j] for row in a), Fraction(0)) for j in range(n)]
              + [sum((row[i] * bk for row, bk in zip(a, b, strict=True)), Fraction(0))] for i in range(n)]
    pivots: list[int] = []
    r = 0
    for col in range(n):
        pivot = next((k for k in range(r, n) if normal[k][col] != 0), None)
        if pivot is None:
            continue
        normal[r], normal[pivot] = normal[pivot], normal[r]
        lead = normal[r][col]
        normal[r] = [value / lead for value in normal[r]]
        for k in range(n):
            if k != r and normal[k][col] != 0:
                factor = normal[k][col]
                normal[k] = [x - factor * y for x, y in zip(normal[k], normal[r], strict=True)]
        pivots.append(col)
        r += 1
    x = [Fraction(0)] * n
    for row, col in zip(normal, pivots, strict=False):
        x[col] = row[n]
    return [float(value) for value in x]
