"""WRONG: forward Euler instead of the exact arc (drifts measurably in x, y)."""
import math


def move(x, y, theta, vel_r, vel_l, R, L, dt):
    v = R / 2 * (vel_r + vel_l)
    w = R / L * (vel_r - vel_l)
    return x + v * dt * math.cos(theta), y + v * dt * math.sin(theta), theta + w * dt
