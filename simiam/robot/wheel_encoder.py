"""`WheelEncoder`: integer ticks from the wheel angle, rounded half away from zero, remainder carried."""

from __future__ import annotations

import math

from simiam.robot.rounding import round_half_away

PI = math.pi
TWO_PI = 2 * math.pi  # exact: a doubling


class WheelEncoder:
    """One wheel's encoder. `ticks` is the cumulative count; the fractional wheel angle is carried over."""

    __slots__ = ("ticks_per_rev", "ticks", "residual")

    def __init__(self, ticks_per_rev: int = 16) -> None:
        self.ticks_per_rev = ticks_per_rev
        self.ticks = 0
        self.residual = 0.0  # wheel angle (rad) not yet counted, within +-pi/ticks_per_rev

    def update(self, vel: float, dt: float) -> int:
        """Advance by wheel speed `vel` (rad/s, the limited speed) over dt; returns the ticks added."""
        residual = self.residual + vel * dt
        tpr = self.ticks_per_rev
        k = round_half_away(residual * tpr / TWO_PI)
        self.residual = residual - k * 2 * PI / tpr  # (k*2)*pi/tpr, in this order
        self.ticks += k
        return k
