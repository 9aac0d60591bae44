"""T(x, y, theta) applied to points, as the original did it.

The original multiplies `vertex_set * T'`; its BLAS evaluated each coordinate with fused multiply-add:
x_w = fl(fma(y, -sin, fl(x*cos)) + t_x), y_w = fl(fma(y, cos, fl(x*sin)) + t_y). `transform_point`
reproduces that bit for bit (exact rational arithmetic, for set-up work such as world files and sensor
mounts, and for the rare steps where the last bits decide; see `fast_error`). `transform_fast` is the plain
form used every step; it differs by at most an ulp or so.
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


def transform_exact(pose: Pose, points: Sequence[tuple[float, float]]) -> tuple[list[float], list[float]]:
    """T(pose) applied to many points bit for bit as the original (slow); returns (xs, ys)."""
    x, y, theta = pose
    c, s = math.cos(theta), math.sin(theta)
    pairs = [(_fma(py, -s, px * c) + x, _fma(py, c, px * s) + y) for px, py in points]
    return [p[0] for p in pairs], [p[1] for p in pairs]


def fast_error(reach: float, extent: float) -> float:
    """A bound on |transform_fast - transform_exact| in each coordinate, for points within `reach` of the
    frame's origin (|px|, |py| <= reach) landing within `extent` of the world's origin (|x_w|, |y_w|).

    Both share fl(px*c); the plain form rounds s*py before subtracting (error <= u*|s*py|), and each form
    rounds the difference (<= u*|t|, |t| <= 2*reach) and the sum with the translation (<= u*extent), with
    u = 2**-53: together at most u*(5*reach + 2*extent) plus terms in u**2. 2**-51*(3*reach + extent) covers
    that with room to spare."""
    return 2.0 ** -51 * (3 * reach + extent)


def transform_fast(pose: Pose, points: Sequence[tuple[float, float]]) -> tuple[list[float], list[float]]:
    """T(pose) applied to many points, plain arithmetic; returns (xs, ys)."""
    x, y, theta = pose
    c, s = math.cos(theta), math.sin(theta)
    return ([c * px - s * py + x for px, py in points], [s * px + c * py + y for px, py in points])
