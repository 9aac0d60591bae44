"""simiam.physics.transform's fused multiply-add (the original's BLAS rounding, bit for bit): the exact
a*b + c rounded once, as exact rational arithmetic gives it."""

from __future__ import annotations

import math
import random
from fractions import Fraction

from simiam.physics.transform import _fma, transform_point


def _exact(a: float, b: float, c: float) -> float:
    return float(Fraction(a) * Fraction(b) + Fraction(c))


def test_fma_rounds_once_like_exact_rational_arithmetic():
    rng = random.Random(15)
    cases = [(0.1, 0.2, 0.3), (-0.0, 1.0, 0.0), (0.0, -1.0, -0.0), (5e-324, 0.5, 0.0), (1e308, 1.5, -1e308),
             (3, 0.1, 2), (1.0, 1e-300, -1e-300), (2.0 ** 52 + 1, 2.0 ** 52 - 1, -(2.0 ** 104))]
    cases += [(rng.uniform(-2, 2), rng.uniform(-1, 1), rng.uniform(-3, 3)) for _ in range(20000)]
    cases += [(rng.uniform(-1, 1) * 10 ** rng.randint(-30, 30), rng.uniform(-1, 1), rng.uniform(-1, 1))
              for _ in range(5000)]
    assert all(_fma(a, b, c) == _exact(a, b, c) for a, b, c in cases)
    # rounding twice (a*b, then + c) differs on some of these: the test tells a plain expression apart
    assert sum(a * b + c != _exact(a, b, c) for a, b, c in cases) > 100


def test_transform_point_is_the_originals_fma_evaluation():
    """x_w = fl(fma(y, -sin, fl(x*cos)) + t_x), y_w = fl(fma(y, cos, fl(x*sin)) + t_y)."""
    import math

    rng = random.Random(7)
    for _ in range(2000):
        pose = (rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-4, 4))
        px, py = rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)
        c, s = math.cos(pose[2]), math.sin(pose[2])
        expected = (_exact(py, -s, px * c) + pose[0], _exact(py, c, px * s) + pose[1])
        assert transform_point(pose, px, py) == expected


def test_fma_rounds_ties_to_even():
    """Exact sums halfway between two doubles: a*b = ulp(c)/2 (a power of two times a double, exact) added
    to c, and products that only the single rounding keeps (1 +- 2**-52 squared)."""
    rng = random.Random(16)
    cases = [(1 + 2 ** -52, 1 - 2 ** -52, 2 ** -53 + 2 ** -104),      # 1 + 2**-53: down to 1.0
             (1 + 2 ** -52, 1 - 2 ** -52, 3 * 2 ** -53 + 2 ** -104),  # 1 + 3*2**-53: up to 1 + 2**-51
             (-(1 + 2 ** -52), 1 - 2 ** -52, -(2 ** -53 + 2 ** -104))]
    for _ in range(5000):
        # every one of the 53 significand bits random, the last (which decides the tie) included
        c = math.ldexp(rng.getrandbits(52) | 2 ** 52, rng.randint(-80, -30)) * rng.choice([1, -1])
        scale = 2.0 ** rng.randint(-5, 5)
        cases.append((scale, math.ulp(c) / 2 / scale * rng.choice([1, -1]), c))
    assert all(_fma(a, b, c) == _exact(a, b, c) for a, b, c in cases)
    assert _fma(*cases[0]) == 1.0 and _fma(*cases[1]) == 1 + 2 ** -51
    halfway = [float(Fraction(a) * Fraction(b) + Fraction(c)) for a, b, c in cases[3:]]
    assert sum(h != c for h, (_, _, c) in zip(halfway, cases[3:], strict=True)) > 1000  # ties go both ways
