"""MATLAB's `round`: half away from zero, exact (Python's `round` rounds half to even)."""

from __future__ import annotations

from math import floor


def round_half_away(x: float) -> int:
    """Round to the nearest integer, halves away from zero, as MATLAB's `round` does, for every double.

    Not floor(x + 0.5): that sum is rounded before the floor, so the largest double below 0.5 (0.5 - 2**-54)
    would count as 1 and an odd integer above 2**52 as the next even one. Here x - floor(x) is exact
    (Sterbenz's lemma for |x| >= 1, x itself below), so only the comparison with one half decides.
    """
    if x >= 0.0:
        whole = floor(x)
        return whole + 1 if x - whole >= 0.5 else whole
    whole = floor(-x)  # whole + x = -(|x| - floor(|x|)), exact as above
    return -whole - 1 if whole + x <= -0.5 else -whole
