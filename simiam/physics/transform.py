"""T(x, y, theta) applied to points, as the original did it.

The original multiplies `vertex_set * T'`; its BLAS evaluated each coordinate with fused multiply-add:
x_w = fl(fma(y, -sin, fl(x*cos)) + t_x), y_w = fl(fma(y, cos, fl(x*sin)) + t_y). `transform_point`
reproduces that bit for bit (exact rational arithmetic, for set-up work such as world files and sensor
mounts). `transform_fast` is the plain form used every step; it differs by at most an ulp or so.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

Pose = tuple[float, float, float]


def _fma(a: float, b: float, c: float) -> float:
    """a*b + c with a single rounding: the exact sum as one ratio of integers, then Python's correctly
    rounded integer division (what float(Fraction(a) * Fraction(b) + Fraction(c)) computes, without
    importing fractions and decimal into every process that loads a world)."""
    an, ad = a.as_integer_ratio()
    bn, bd = b.as_integer_ratio()
    cn, cd = c.as_integer_ratio()
    return (an * bn * cd + cn * ad * bd) / (ad * bd * cd)


def transform_point(pose: Pose, px: float, py: float) -> tuple[float, float]:
    """T(pose) * [px; py; 1], bit-exact with the original's fma evaluation (slow: set-up only)."""
    x, y, theta = pose
    c, s = math.cos(theta), math.sin(theta)
    return _fma(py, -s, px * c) + x, _fma(py, c, px * s) + y


def transform_fast(pose: Pose, points: Sequence[tuple[float, float]]) -> tuple[list[float], list[float]]:
    """T(pose) applied to many points, plain arithmetic; returns (xs, ys)."""
    x, y, theta = pose
    c, s = math.cos(theta), math.sin(theta)
    return ([c * px - s * py + x for px, py in points], [s * px + c * py + y for px, py in points])
