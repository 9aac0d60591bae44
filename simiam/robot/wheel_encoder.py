"""`WheelEncoder`: integer ticks from the wheel angle, rounded half away from zero, remainder carried."""

from __future__ import annotations

import math
from math import floor

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
        x = residual * tpr / TWO_PI
        # round_half_away(x) written out, branch for branch (its docstring says why not floor(x + 0.5)):
        # two encoders a step, and the call was a third of the update
        if x >= 0.0:
            k = floor(x)
            if x - k >= 0.5:
                k += 1
        else:
            k = floor(-x)
            k = -k - 1 if k + x <= -0.5 else -k
        self.residual = residual - k * 2 * PI / tpr  # (k*2)*pi/tpr, in this order
        self.ticks += k
        return k
