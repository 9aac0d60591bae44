"""MATLAB's `round`: half away from zero (Python's `round` rounds half to even)."""

from __future__ import annotations

import math


def round_half_away(x: float) -> int:
    """Round to the nearest integer, halves away from zero, as MATLAB's `round` does."""
    if x >= 0.0:
        return int(math.floor(x + 0.5))
    return -int(math.floor(-x + 0.5))
