"""validate.py against untrusted values, and the naive float() it replaces."""

from __future__ import annotations

import math

import pytest
from sandbox_wrong import naive

from grader.sandbox.validate import BadValue, as_float, as_float_list, as_matrix

BAD_NUMBERS = [(True, "True \\(a bool\\)"), ("1.5", "a str"), (None, "None"), (math.nan, "NaN"),
               (math.inf, "infinity"), (-math.inf, "minus infinity"), ([1.0], "a list of 1"),
               ({"x": 1}, "a dict"), (10**400, "too large")]


@pytest.mark.parametrize("value, message", BAD_NUMBERS)
def test_as_float_refuses_with_a_message(value, message):
    with pytest.raises(BadValue, match=f"your uni_to_diff returned .*{message}"):
        as_float(value, "your uni_to_diff returned")


def test_naive_float_accepts_most_of_them():
    accepted = 0
    for value, _ in BAD_NUMBERS:
        try:
            naive.as_float(value)
            accepted += 1
        except (TypeError, ValueError, OverflowError):
            pass
    assert accepted >= 5


def test_as_float_accepts_ints_and_floats():
    assert as_float(3) == 3.0 and type(as_float(3)) is float
    assert as_float(-2.5) == -2.5
    assert as_float(1e308) == 1e308


def test_as_float_list():
    assert as_float_list([1, 2.5], 2) == [1.0, 2.5]
    with pytest.raises(BadValue, match="your uni_to_diff returned a str, expected two numbers"):
        as_float_list("3.8, 2.3", 2, "your uni_to_diff returned")
    with pytest.raises(BadValue, match="returned 3 values, expected two numbers"):
        as_float_list([1, 2, 3], 2, "returned")
    with pytest.raises(BadValue, match=r"\(item 2\) NaN"):
        as_float_list([1, math.nan], 2, "returned")


def test_as_matrix():
    eye = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    assert as_matrix(eye, 3, 3) == [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    with pytest.raises(BadValue, match="a 3x2 matrix, expected a 3x3 matrix"):
        as_matrix([[1, 0], [0, 1], [0, 0]], 3, 3, "T is")
    with pytest.raises(BadValue, match="a list of 2, expected a 3x5 matrix"):
        as_matrix([1, 2], 3, 5, "ir_distances_rf is")
    with pytest.raises(BadValue, match=r"row 2, column 1\) a str"):
        as_matrix([[1, 0, 0], ["0", 1, 0], [0, 0, 1]], 3, 3, "T is")
