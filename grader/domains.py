"""What a property check tries: input domains that sample themselves, or become Hypothesis strategies.

A passing property check never needs Hypothesis's engine (1.2-1.6 ms of CPU per case, 0.1-0.3 s to
import; docs/performance.md). `grader.properties` draws its cases from these domains with a
`random.Random` seeded from the grading seed and the check id, so a regrade tries the same inputs, and
turns a domain into the same `hypothesis.strategies` value (`strategy()`) only when a case failed and the
failure is to be shrunk into the smallest counterexample.

Uniform sampling alone would miss mistakes that only show at the edges, where Hypothesis looks first:
the bounds, 0 and -0.0, tiny and subnormal numbers, +-1, +-pi/2, +-pi, empty and longest lists. So the
first case is the simplest value of every input (what Hypothesis tries first), the second every input at
its lower end and the third at its upper end; in the later cases every number is one of the special
values with probability `EDGE_RATE` (half of those at the bounds), else uniform in its range.
"""

from __future__ import annotations

import math
import random
import sys
from collections.abc import Callable, Sequence
from typing import Any

EDGE_RATE = 0.25  # chance that one drawn number is a special value rather than uniform in its range

# The special floats Hypothesis's generator favours (hypothesis.internal.conjecture.providers), plus the
# angles a heading check turns on. Each domain keeps those inside its range, with both signs.
_SPECIAL = (0.5, 1.0, 1.1, 1.5, 1.9, 1.0 / 3, 10e-6, 1 - 10e-6, 2 + 10e-6, 1.192092896e-07,
            2.2204460492503131e-16, 1.175494351e-38, sys.float_info.min, math.ulp(0.0),
            math.pi / 2, math.pi, 2 * math.pi, 2.0, 3.0)


class Domain:
    """The values one input of a property takes: `draw` one (seeded), or the Hypothesis `strategy()`."""

    def simplest(self) -> Any:
        """The value Hypothesis tries first and shrinks towards."""
        raise NotImplementedError

    def low(self) -> Any:
        """The value at the lower end (the lower bound, the shortest list of them): tried second."""
        raise NotImplementedError

    def high(self) -> Any:
        """The value at the upper end (the upper bound, the longest list of them): tried third."""
        raise NotImplementedError

    def draw(self, rng: random.Random) -> Any:
        raise NotImplementedError

    def strategy(self) -> Any:
        raise NotImplementedError

    def filter(self, keep: Callable[[Any], bool]) -> Domain:
        """The values of this domain for which `keep` is true (as Hypothesis's `.filter`)."""
        return Filtered(self, keep)


class Filtered(Domain):
    """The values of a domain that pass a test, e.g. speeds not too close to 0. Draws again on a miss."""

    TRIES = 100

    def __init__(self, base: Domain, keep: Callable[[Any], bool]) -> None:
        self.base, self.keep = base, keep

    def simplest(self) -> Any:
        first = self.base.simplest()
        if self.keep(first):
            return first
        kept = [v for v in getattr(self.base, "edges", ()) if self.keep(v)]
        if kept:
            return min(kept, key=abs)
        return self.draw(random.Random(0))

    def low(self) -> Any:
        value = self.base.low()
        return value if self.keep(value) else self.draw(random.Random(1))

    def high(self) -> Any:
        value = self.base.high()
        return value if self.keep(value) else self.draw(random.Random(2))

    def draw(self, rng: random.Random) -> Any:
        for _ in range(self.TRIES):
            value = self.base.draw(rng)
            if self.keep(value):
                return value
        raise ValueError(f"{self!r}: no value passed the filter in {self.TRIES} draws")

    def strategy(self) -> Any:
        return self.base.strategy().filter(self.keep)

    def __repr__(self) -> str:
        return f"{self.base!r}.filter(...)"


class Floats(Domain):
    """A float in [lo, hi] (bounds included; never NaN or infinite)."""

    def __init__(self, lo: float, hi: float) -> None:
        if not lo <= hi:
            raise ValueError(f"Floats({lo}, {hi}): empty range")
        self.lo, self.hi = float(lo), float(hi)
        self.bounds = sorted({self.lo, self.hi, math.nextafter(self.lo, hi), math.nextafter(self.hi, lo)})
        inside = {v for s in _SPECIAL for v in (s, -s) if lo <= v <= hi} - set(self.bounds)
        self.specials = sorted(inside) + ([0.0, -0.0] if lo <= 0.0 <= hi else [])
        self.edges = self.bounds + self.specials

    def simplest(self) -> float:
        return 0.0 if self.lo <= 0.0 <= self.hi else min(self.lo, self.hi, key=abs)

    def low(self) -> float:
        return self.lo

    def high(self) -> float:
        return self.hi

    def draw(self, rng: random.Random) -> float:
        if rng.random() < EDGE_RATE:  # half of the special values at the bounds: mistakes live there
            return rng.choice(self.bounds if rng.random() < 0.5 or not self.specials else self.specials)
        return min(self.hi, max(self.lo, rng.uniform(self.lo, self.hi)))

    def strategy(self) -> Any:
        from hypothesis import strategies as st

        return st.floats(self.lo, self.hi, allow_nan=False, allow_infinity=False)

    def __repr__(self) -> str:
        return f"Floats({self.lo!r}, {self.hi!r})"


class Integers(Domain):
    """An int in [lo, hi] (bounds included)."""

    def __init__(self, lo: int, hi: int) -> None:
        if not lo <= hi:
            raise ValueError(f"Integers({lo}, {hi}): empty range")
        self.lo, self.hi = int(lo), int(hi)
        self.edges = sorted({v for v in (lo, hi, 0, 1, -1, lo + 1, hi - 1) if lo <= v <= hi})

    def simplest(self) -> int:
        return 0 if self.lo <= 0 <= self.hi else min(self.lo, self.hi, key=abs)

    def low(self) -> int:
        return self.lo

    def high(self) -> int:
        return self.hi

    def draw(self, rng: random.Random) -> int:
        if rng.random() < EDGE_RATE:
            return rng.choice(self.edges)
        return rng.randint(self.lo, self.hi)

    def strategy(self) -> Any:
        from hypothesis import strategies as st

        return st.integers(self.lo, self.hi)

    def __repr__(self) -> str:
        return f"Integers({self.lo}, {self.hi})"


class SampledFrom(Domain):
    """One of a few fixed values (e.g. the time steps the course uses)."""

    def __init__(self, values: Sequence[Any]) -> None:
        if not values:
            raise ValueError("SampledFrom: no values")
        self.values = list(values)

    def simplest(self) -> Any:
        return self.values[0]

    def low(self) -> Any:
        return self.values[0]

    def high(self) -> Any:
        return self.values[-1]

    def draw(self, rng: random.Random) -> Any:
        return rng.choice(self.values)

    def strategy(self) -> Any:
        from hypothesis import strategies as st

        return st.sampled_from(self.values)

    def __repr__(self) -> str:
        return f"SampledFrom({self.values!r})"


class Lists(Domain):
    """A list of `min_size`..`max_size` values of `elements`; the shortest and longest are edges."""

    def __init__(self, elements: Domain, min_size: int = 0, max_size: int = 10) -> None:
        if not 0 <= min_size <= max_size:
            raise ValueError(f"Lists: bad sizes {min_size}..{max_size}")
        self.elements, self.min_size, self.max_size = elements, min_size, max_size

    def simplest(self) -> list:
        return [self.elements.simplest() for _ in range(self.min_size)]

    def low(self) -> list:
        return [self.elements.low() for _ in range(self.min_size)]

    def high(self) -> list:
        return [self.elements.high() for _ in range(self.max_size)]

    def draw(self, rng: random.Random) -> list:
        if rng.random() < EDGE_RATE:
            size = rng.choice((self.min_size, self.max_size))
        else:
            size = rng.randint(self.min_size, self.max_size)
        return [self.elements.draw(rng) for _ in range(size)]

    def strategy(self) -> Any:
        from hypothesis import strategies as st

        return st.lists(self.elements.strategy(), min_size=self.min_size, max_size=self.max_size)

    def __repr__(self) -> str:
        return f"Lists({self.elements!r}, {self.min_size}, {self.max_size})"


class Row(Domain):
    """A fixed-length list with one domain per place, e.g. a start pose [x, y, theta] or a tick pair."""

    def __init__(self, *places: Domain) -> None:
        self.places = places

    def simplest(self) -> list:
        return [p.simplest() for p in self.places]

    def low(self) -> list:
        return [p.low() for p in self.places]

    def high(self) -> list:
        return [p.high() for p in self.places]

    def draw(self, rng: random.Random) -> list:
        return [p.draw(rng) for p in self.places]

    def strategy(self) -> Any:
        from hypothesis import strategies as st

        return st.tuples(*(p.strategy() for p in self.places)).map(list)

    def __repr__(self) -> str:
        return f"Row{self.places!r}"
