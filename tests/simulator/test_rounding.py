"""simiam.robot.rounding: MATLAB's round (half away from zero), exact for every double, against exact
rational arithmetic. The encoders and the IR ADC both round with it."""

from __future__ import annotations

import math
import random
from fractions import Fraction

from simiam.robot.rounding import round_half_away


def matlab_round(x: float) -> int:
    """The exact rule: the nearest integer, halves away from zero (Fraction: no rounding on the way)."""
    q = abs(Fraction(x))
    n = int(q + Fraction(1, 2))  # floor of |x| + 1/2, computed exactly
    return n if x >= 0 else -n


def near_halves() -> list[float]:
    """Halves and their neighbours a few ulps either side, from 0.5 up to 2**53, both signs."""
    out = []
    for k in [0, 1, 2, 3, 133, 916, 917, 1374, 2 ** 20, 2 ** 51, 2 ** 52 - 1]:
        h = k + 0.5
        for x in (h, math.nextafter(h, 0), math.nextafter(h, math.inf)):
            for _ in range(3):
                out += [x, -x]
                x = math.nextafter(x, 0)
    return out


def test_exact_at_halves_and_their_neighbours():
    cases = near_halves() + [0.0, -0.0, 0.25, 1e-300, 5e-324, 2.0 ** 52 + 1, 2.0 ** 53 + 2, 1e300, -1e300]
    assert [round_half_away(x) for x in cases] == [matlab_round(x) for x in cases]


def test_the_largest_double_below_a_half_rounds_down():
    """floor(x + 0.5) gives 1 here: 0.5 - 2**-54 + 0.5 rounds (ties to even) to 1.0 before the floor."""
    x = math.nextafter(0.5, 0)
    assert (round_half_away(x), round_half_away(-x)) == (0, 0)
    # and above 2**52, where x + 0.5 rounds to the even neighbour: 2**52 + 1 is already an integer
    assert round_half_away(2.0 ** 52 + 1) == 2 ** 52 + 1


def test_random_values_of_every_magnitude():
    rng = random.Random(20)
    cases = [rng.uniform(-3, 3) for _ in range(20000)]
    cases += [rng.uniform(-1, 1) * 2.0 ** rng.randint(-60, 60) for _ in range(20000)]
    assert [round_half_away(x) for x in cases] == [matlab_round(x) for x in cases]
