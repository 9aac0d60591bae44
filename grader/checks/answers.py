"""Reading the student's untrusted answers: plain numbers, vectors and matrices, or a Mismatch saying why not.

The worker sends JSON; a NaN or infinity arrives as the string "nan"/"inf" (see grader.inside.probing.plain)
and an object the worker could not turn into numbers arrives as {"type": name}. Only real ints and
floats pass.
"""

from __future__ import annotations

from typing import Any

from grader.checks import Mismatch
from grader.sandbox.validate import BadValue, as_float


def describe(value: Any) -> str:
    """A short, student-readable description of an answer that is not what was expected."""
    if isinstance(value, dict) and "type" in value:
        return f"a {value['type']} object"
    if isinstance(value, str):
        return (
            "NaN" if value.lower() == "nan" else ("infinity" if "inf" in value.lower() else repr(value[:40]))
        )
    if value is None:
        return "None"
    if type(value) is bool:
        return f"{value} (a bool)"
    if type(value) is float and value != value:
        return "NaN"
    if isinstance(value, list):
        return f"a list of {len(value)} values"
    text = repr(value)
    return text if len(text) < 60 else text[:57] + "..."


def number(value: Any, what: str) -> float:
    """A finite float (the sandbox's own type gate decides), or Mismatch("<what> was NaN, expected ...")."""
    try:
        return as_float(value, what)
    except BadValue:
        raise Mismatch(f"{what} was {describe(value)}, expected a finite number") from None


def floats(value: Any, n: int) -> list[float] | None:
    """`value` if it is a list of exactly n finite floats (what an honest answer almost always is), else
    None: `vector` then says what is wrong. Spares the thousands of probed vectors of a property check
    the messages they would need only if they were wrong."""
    if type(value) is list and len(value) == n and all(type(v) is float for v in value):
        total = sum(value)
        if total - total == 0.0:  # every value finite (a sum that overflows takes vector's long way)
            return list(value)
    return None


def vector(value: Any, n: int, what: str) -> list[float]:
    """Exactly n finite numbers (a list or tuple of them, or a numpy array turned into a list)."""
    plain = floats(value, n)
    if plain is not None:
        return plain
    if not isinstance(value, list) or len(value) != n:
        raise Mismatch(f"{what} was {describe(value)}, expected {n} numbers")
    return [number(v, f"{what} (value {i + 1} of {n})") for i, v in enumerate(value)]


def matrix(value: Any, rows: int, cols: int, what: str) -> list[list[float]]:
    """A rows x cols matrix of finite numbers (a list of rows)."""
    if not isinstance(value, list) or len(value) != rows or not all(isinstance(r, list) for r in value):
        raise Mismatch(f"{what} was {describe(value)}, expected a {rows}x{cols} matrix")
    out = []
    for i, row in enumerate(value):
        if len(row) != cols:
            raise Mismatch(
                f"{what} row {i + 1} has {len(row)} values, expected {cols} ({rows}x{cols} matrix)"
            )
        out.append([number(v, f"{what} (row {i + 1}, column {j + 1})") for j, v in enumerate(row)])
    return out


def fmt(x: float) -> str:
    """A number as a student reads it: up to 4 significant decimals, no trailing noise, and an ASCII minus
    (students paste these numbers into Python)."""
    if x == 0:
        return "0"
    return f"{x:.4g}" if abs(x) < 1e-3 or abs(x) >= 1e4 else f"{x:.4f}".rstrip("0").rstrip(".")


WILD = 10.0  # a relative error beyond 1000 % is not a figure worth reading


def off_by(relative: float) -> str:
    """'12 % off', or 'wildly off' when the figure would be absurd (222121189413483552 % off)."""
    if not relative <= WILD:  # NaN too
        return f"wildly off (more than {WILD * 100:.0f} % from it)"
    return f"{relative:.0%} off"


def amount(x: float, unit: str, sane: float) -> str:
    """`x unit`, or 'wildly off (x unit)' when |x| is far beyond `sane` (a distance of -8.9e13 m)."""
    text = f"{fmt(x)} {unit}".rstrip()
    return text if abs(x) <= sane else f"wildly off ({text})"
