"""The QuickBot as the original simulator built it: dimensions, limits, base plate, IR mounts, per week.

All values come from `+simiam/+robot/QuickBot.m` (sp14 and the weekly branches); see
`reference/original-simulator.md` section 1 and the contract's robot table.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

WHEEL_RADIUS = 0.0325
WHEEL_BASE_LENGTH = 0.09925
TICKS_PER_REV = 16

# max/min wheel speeds, written as the original computes them (rpm * 2*pi / 60), so that the bits
# match: 30*2*pi/60 is one ulp below pi and decides the dead-zone quirk.
MAX_VEL_80RPM = 80 * 2 * math.pi / 60
MAX_VEL_130RPM = 130 * 2 * math.pi / 60
MIN_VEL_30RPM = 30 * 2 * math.pi / 60

# The collision body `qb_base_plate`, body frame, counter-clockwise.
BASE_PLATE: tuple[tuple[float, float], ...] = (
    (0.0335, 0.0534), (0.0429, 0.0534), (0.0639, 0.0334), (0.0686, 0.0), (0.0639, -0.0334),
    (0.0429, -0.0534), (0.0335, -0.0534), (-0.0465, -0.0534), (-0.0815, -0.0534), (-0.1112, -0.0387),
    (-0.1112, 0.0387), (-0.0815, 0.0534), (-0.0465, 0.0534),
)


def deg2rad(d: float) -> float:
    """MATLAB's deg2rad, in its operation order (d*pi/180)."""
    return d * math.pi / 180


# IR mounting poses (x, y, theta) in the body frame; index 0..4 = the manual's sensors 1..5.
# Deliberately not mirror-symmetric, as in the original.
IR_MOUNTS: tuple[tuple[float, float, float], ...] = (
    (-0.0474, 0.0534, deg2rad(90)),
    (0.0613, 0.0244, deg2rad(45)),
    (0.0636, 0.0, deg2rad(0)),
    (0.0461, -0.0396, deg2rad(-45)),
    (-0.0690, -0.0534, deg2rad(-90)),
)

IR_MIN_RANGE = 0.04
IR_MAX_RANGE = 0.3
IR_SPREAD = deg2rad(6)


@dataclass(frozen=True)
class RobotSpec:
    """What the trusted simulator needs to know about the robot in one week of the course.

    `ir_mode` is "week2" (the week-2 divider: raw = round(500*V), clamped to [200, 1375]) or
    "week3" (raw = round(1000*V/3), clamped to [133, 917]). Speeds are wheel angular speeds in rad/s.
    `brain_first`: each step runs the supervisor before it moves the robot (the original's week-1 order);
    otherwise the robot first moves with last step's speeds. Each week declares its spec in
    simiam/course/weeks/weekN.py.
    """

    week: int
    max_vel: float
    min_vel: float
    ir_mode: str
    brain_first: bool = False
    wheel_radius: float = WHEEL_RADIUS
    wheel_base_length: float = WHEEL_BASE_LENGTH
    ticks_per_rev: int = TICKS_PER_REV
    base_plate: tuple[tuple[float, float], ...] = BASE_PLATE
    ir_mounts: tuple[tuple[float, float, float], ...] = IR_MOUNTS
    ir_min_range: float = IR_MIN_RANGE
    ir_max_range: float = IR_MAX_RANGE
    ir_spread: float = IR_SPREAD

    def limit_speeds(self, vel_r: float, vel_l: float) -> tuple[float, float]:
        """Clamp each wheel to +-max_vel, then zero a wheel below min_vel (strict: kept at |w| >= min_vel)."""
        return limit_speeds(vel_r, vel_l, self.max_vel, self.min_vel)


def limit_speeds(vel_r: float, vel_l: float, max_vel: float, min_vel: float) -> tuple[float, float]:
    """`QuickBot.limit_speeds`: clamp to +-max_vel, then the strict dead zone (kept when |w| >= min_vel)."""
    # max(min(v, max_vel), -max_vel) without the calls: min keeps v unless max_vel < v, max keeps it unless
    # -max_vel > it (the same value for every v, -0.0 and nan included)
    if vel_r > max_vel:
        vel_r = max_vel
    if vel_r < -max_vel:
        vel_r = -max_vel
    if vel_l > max_vel:
        vel_l = max_vel
    if vel_l < -max_vel:
        vel_l = -max_vel
    if abs(vel_r) < min_vel:
        vel_r = 0.0
    if abs(vel_l) < min_vel:
        vel_l = 0.0
    return vel_r, vel_l
