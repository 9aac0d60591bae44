"""Differential-drive kinematics: the exact arc per step, from the wheel speeds through diff_to_uni.

The original integrates with ode45 at 1e-8 over a step with constant wheel speeds; the exact arc agrees
with it to ~1e-12. The arc is evaluated in chord form (length v*dt*sinc(w*dt/2) along the mid heading),
which stays accurate when w*dt is tiny. The true heading is never wrapped. The physics never needs
uni_to_diff (a student block): it integrates wheel speeds; the reference one lives with the instructor's
tooling (instructor_tools/reference_maths.py).
"""

from __future__ import annotations

import math
from math import cos, sin


def diff_to_uni(R: float, L: float, vel_r: float, vel_l: float) -> tuple[float, float]:
    """Wheel speeds -> unicycle (v, w), in the original's operation order: R/2*(r+l), R/L*(r-l)."""
    v = R / 2 * (vel_r + vel_l)
    w = R / L * (vel_r - vel_l)
    return v, w


def _sinc(a: float) -> float:
    """sin(a)/a, with its Taylor series near 0 (where the quotient loses digits)."""
    if abs(a) < 1e-4:
        a2 = a * a
        return 1.0 - a2 / 6.0 + a2 * a2 / 120.0
    return math.sin(a) / a


def move(x: float, y: float, theta: float, vel_r: float, vel_l: float,
         R: float, L: float, dt: float) -> tuple[float, float, float]:
    """The pose after dt with constant wheel speeds: the exact arc, in chord form."""
    # diff_to_uni and _sinc written out, the same operations in the same order: every step moves the
    # robot, and the two calls cost a third of the move
    v = R / 2 * (vel_r + vel_l)
    w = R / L * (vel_r - vel_l)
    if w == 0.0:
        return x + v * dt * cos(theta), y + v * dt * sin(theta), theta
    half = w * dt / 2
    if abs(half) < 1e-4:
        a2 = half * half
        chord = v * dt * (1.0 - a2 / 6.0 + a2 * a2 / 120.0)
    else:
        chord = v * dt * (sin(half) / half)
    heading = theta + half
    return x + chord * cos(heading), y + chord * sin(heading), theta + w * dt


def move_arc(x: float, y: float, theta: float, vel_r: float, vel_l: float,
             R: float, L: float, dt: float) -> tuple[float, float, float]:
    """The same exact arc in the textbook form (v/w)(sin(theta+w dt) - sin theta); kept to cross-check."""
    v, w = diff_to_uni(R, L, vel_r, vel_l)
    if w == 0.0:
        return x + v * dt * math.cos(theta), y + v * dt * math.sin(theta), theta
    t1 = theta + w * dt
    return x + v / w * (math.sin(t1) - math.sin(theta)), y - v / w * (math.cos(t1) - math.cos(theta)), t1
