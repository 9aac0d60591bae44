"""WRONG: wraps the true heading to (-pi, pi] (the original never wraps it)."""
import math

from simiam.robot.dynamics import move as _move


def move(x, y, theta, vel_r, vel_l, R, L, dt):
    x, y, theta = _move(x, y, theta, vel_r, vel_l, R, L, dt)
    return x, y, math.atan2(math.sin(theta), math.cos(theta))
