"""WRONG: rounds each step's wheel angle on its own and drops the remainder."""
import math


class WheelEncoder:
    def __init__(self, ticks_per_rev=16):
        self.ticks_per_rev = ticks_per_rev
        self.ticks = 0

    def update(self, vel, dt):
        k = math.floor(vel * dt * self.ticks_per_rev / (2 * math.pi) + 0.5)
        self.ticks += k
        return k
