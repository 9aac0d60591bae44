"""`vector`'s fast path (`floats`, issue 24) gives exactly what the checked path gives, and a wrong answer
still gets its words: every kind of value a worker may send is tried both ways."""

from __future__ import annotations

import math

import pytest

from grader.checks import Mismatch
from grader.checks.answers import floats, number, vector


def _checked(value, n: int, what: str) -> list[float]:
    """The long way only (vector before the fast path)."""
    if not isinstance(value, list) or len(value) != n:
        raise Mismatch(f"{what} was ..., expected {n} numbers")
    return [number(v, f"{what} (value {i + 1} of {n})") for i, v in enumerate(value)]


def _without_finiteness(value, n: int):
    """Wrong version kept: the fast path that trusts the types alone."""
    if type(value) is list and len(value) == n and all(type(v) is float for v in value):
        return list(value)
    return None


ODD = [[1.0, 2.0], [0.0, -0.0], [1e308, 1e308], [-1e308, -1e308], [5e-324, 1.0], [1, 2.0], [True, 1.0],
       [math.nan, 1.0], [1.0, math.inf], [-math.inf, 0.0], [1.0], [1.0, 2.0, 3.0], (1.0, 2.0), None, "ab",
       [[1.0], [2.0]], [None, 1.0], {"x": 1.0}]


@pytest.mark.parametrize("value", ODD, ids=repr)
def test_the_fast_path_gives_what_the_checked_path_gives(value):
    try:
        expected = _checked(value, 2, "your u")
    except Mismatch:
        expected = None
    fast = floats(value, 2)
    assert fast is None or fast == expected  # never a value the checked path refuses
    if expected is None:
        with pytest.raises(Mismatch, match="your u"):
            vector(value, 2, "your u")
    else:
        got = vector(value, 2, "your u")
        assert got == expected and all(type(v) is float for v in got)
        assert [math.copysign(1, v) for v in got] == [math.copysign(1, v) for v in expected]


def test_an_overflowing_sum_of_finite_values_takes_the_long_way_and_keeps_them():
    assert floats([1e308, 1e308], 2) is None
    assert vector([1e308, 1e308], 2, "your u") == [1e308, 1e308]


@pytest.mark.parametrize("value", [[math.nan, 1.0], [1.0, math.inf]])
def test_the_wrong_fast_path_would_let_a_nan_through(value):
    assert _without_finiteness(value, 2) is not None and floats(value, 2) is None
