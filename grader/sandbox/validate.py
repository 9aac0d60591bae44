"""Checks on the untrusted values that come back from the student's worker, with messages students read.

Values arrive as parsed JSON (None, bool, int, float, str, list, dict; NaN and infinities only when the
student really returned them). A check calls, for example,

    vel_r, vel_l = as_float_list(value, 2, "your uni_to_diff returned")

and gets two finite Python floats or a BadValue such as
"your uni_to_diff returned a str, expected two numbers".
"""

from __future__ import annotations

import math
from typing import Any

from grader.sandbox.errors import StudentError

_COUNT = {1: "one", 2: "two", 3: "three", 4: "four", 5: "five"}


class BadValue(StudentError):
    """A value of the wrong type, shape or size (a StudentError, so a check fails with this message)."""

    def __init__(self, message: str) -> None:
        super().__init__(message, "")


def describe(x: Any) -> str:
    """A short, student-readable name of what a value is: "a str", "None", "NaN", "a list of 3"."""
    if x is None:
        return "None"
    if type(x) is bool:
        return f"{x} (a bool)"
    if type(x) is float and not math.isfinite(x):
        return "NaN" if math.isnan(x) else "infinity" if x > 0 else "minus infinity"
    if isinstance(x, list):
        return f"a list of {len(x)}"
    return f"a {type(x).__name__}"


def _numbers(n: int) -> str:
    return f"{_COUNT.get(n, n)} number{'s' if n != 1 else ''}"


def as_float(x: Any, what: str = "the value") -> float:
    """`x` as a finite float; only int and float count (bool, str, None, NaN, infinities are refused)."""
    if type(x) is int:
        try:
            return float(x)
        except OverflowError:
            raise BadValue(f"{what} a number too large to be a float") from None
    if type(x) is not float or not math.isfinite(x):
        raise BadValue(f"{what} {describe(x)}, expected a number")
    return x


def as_float_list(x: Any, n: int, what: str = "the value") -> list[float]:
    """`x` as exactly `n` finite floats (a JSON array; tuples arrive as arrays)."""
    if not isinstance(x, list):
        raise BadValue(f"{what} {describe(x)}, expected {_numbers(n)}")
    if len(x) != n:
        raise BadValue(f"{what} {len(x)} values, expected {_numbers(n)}")
    return [as_float(v, f"{what} (item {i + 1})") for i, v in enumerate(x)]


def as_matrix(x: Any, rows: int, cols: int, what: str = "the value") -> list[list[float]]:
    """`x` as a rows x cols matrix of finite floats (a list of rows)."""
    shape = f"a {rows}x{cols} matrix"
    if not isinstance(x, list) or len(x) != rows or not all(isinstance(r, list) for r in x):
        got = describe(x) if not isinstance(x, list) else _shape(x)
        raise BadValue(f"{what} {got}, expected {shape}")
    if any(len(r) != cols for r in x):
        raise BadValue(f"{what} {_shape(x)}, expected {shape}")
    return [[as_float(v, f"{what} (row {i + 1}, column {j + 1})") for j, v in enumerate(r)]
            for i, r in enumerate(x)]


def _shape(x: list) -> str:
    if all(isinstance(r, list) for r in x):
        widths = sorted({len(r) for r in x})
        cols = widths[0] if len(widths) == 1 else "-".join(map(str, (widths[0], widths[-1])))
        return f"a {len(x)}x{cols} matrix"
    return f"a list of {len(x)}"
