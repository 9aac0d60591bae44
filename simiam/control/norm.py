"""norm(u): the length of a vector, rounded as the original simulator's `norm` rounded it.

The original ran `norm(u)` in MATLAB/Octave, which sums scaled squares: scl * sqrt(sum((|u_i|/scl)^2)),
with scl the largest |u_i| seen so far (rescaling the sum when a larger one comes). That differs from
`math.hypot` or `np.linalg.norm` in the last bit for about 40 % of 2-vectors; a last bit is enough to move
a closed-loop run through the motors' dead zone, so the course solutions use this to match the recorded
runs step for step. Any other correct length (np.linalg.norm, math.hypot) is fine for the assignments.
"""

from __future__ import annotations

import math
from collections.abc import Iterable


def norm(u: Iterable[float]) -> float:
    """The Euclidean length of the vector u (a list, tuple or numpy array of numbers).

    >>> norm([3.0, 4.0])
    5.0
    """
    # Octave's norm_accumulator_2, step by step (liboctave/numeric/oct-norm.cc)
    scl = 0.0
    total = 1.0
    for value in u:
        t = abs(float(value))
        if t != t:  # NaN (Octave's division by a zero scale would give NaN too; Python's would raise)
            return math.nan
        if scl == t:
            total += 1.0
        elif scl < t:
            total *= (scl / t) * (scl / t)
            total += 1.0
            scl = t
        elif t != 0.0:
            total += (t / scl) * (t / scl)
    return scl * math.sqrt(total)
