"""`WheelEncoder`: integer ticks from the wheel angle, rounded half away from zero, remainder carried."""

from __future__ import annotations

import math

from simiam.robot.rounding import round_half_away


class WheelEncoder:
    """One wheel's encoder. `ticks` is the cumulative count; the fractional wheel angle is carried over."""

    __slots__ = ("ticks_per_rev", "ticks", "residual")

    def __init__(self, ticks_per_rev: int = 16) -> None:
        self.ticks_per_rev = ticks_per_rev
        self.ticks = 0
        self.residual = 0.0  # wheel angle (rad) not yet counted, within +-pi/ticks_per_rev

    def update(self, vel: float, dt: float) -> int:
        """Advance by wheel speed `vel` (rad/s, the limited speed) over dt; returns the ticks added."""
        self.residual += vel * dt
        k = round_half_away(self.residual * self.ticks_per_rev / (2 * math.pi))
        self.residual -= k * 2 * math.pi / self.ticks_per_rev
        self.ticks += k
        return k
