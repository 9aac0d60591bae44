"""WRONG: Python's round (half to even) instead of MATLAB's round (half away from zero)."""
import math


class WheelEncoder:
    def __init__(self, ticks_per_rev=16):
        self.ticks_per_rev = ticks_per_rev
        self.ticks = 0
        self.residual = 0.0

    def update(self, vel, dt):
        self.residual += vel * dt
        k = round(self.residual * self.ticks_per_rev / (2 * math.pi))
        self.residual -= k * 2 * math.pi / self.ticks_per_rev
        self.ticks += k
        return k
