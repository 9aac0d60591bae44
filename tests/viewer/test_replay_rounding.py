"""The replay packs its numbers with a rounding faster than round() (simiam.viewer.replay._column): it
must give round()'s float, bit for bit (sign of zero and type included), for every number a trace can
hold; the kept wrong version without the guard near a half does not."""

from __future__ import annotations

import importlib.util
import math
import random
from pathlib import Path

from simiam.viewer.replay import _FAST, _column, _num

WRONG = Path(__file__).resolve().parents[1] / "data" / "viewer_wrong" / "rounding_without_tie_guard.py"
DIGITS = (3, 4, 5, 6)  # what the replay rounds to (replay._DIGITS, _SIGNAL_DIGITS and the world's 5 and 6)


def _numbers(digits: int, seed: int) -> list:
    """Numbers where a rounding goes wrong: exact halves in the last decimal and their neighbours one and a
    few floats away, at every size a trace has (positions, speeds, raw counts, debug values up to far
    beyond the chart) and beyond _FAST; special values; and plain random ones."""
    rng = random.Random(f"{digits}-{seed}")
    scale = 10 ** digits
    out: list = []
    for _ in range(40_000):
        magnitude = 10.0 ** rng.uniform(-digits - 2, 7)
        out.append(rng.choice((-1, 1)) * rng.random() * magnitude)
    for _ in range(20_000):
        half = (rng.randrange(-10 ** 7, 10 ** 7) + 0.5) / scale
        out.append(half)
        up = down = half
        for _ in range(rng.randrange(1, 4)):
            up, down = math.nextafter(up, math.inf), math.nextafter(down, -math.inf)
        out += [up, down]
    for k in range(-2000, 2000):  # every half near zero, where the sign of a zero decides
        out += [(k + 0.5) / scale, math.nextafter((k + 0.5) / scale, 0.0)]
    edge = _FAST / scale
    out += [edge, -edge, math.nextafter(edge, 0.0), math.nextafter(-edge, 0.0), edge * 2, 1e300, -1e300,
            math.inf, -math.inf, math.nan, 0.0, -0.0, 5e-324, -5e-324, 2.0 ** 52, 0.5, -0.5, 1.5, 2.5]
    out += [None, True, False, 0, -3, 7, 10 ** 20, "1.5", [1.0]]
    return out


def _same(a: object, b: object) -> bool:
    if type(a) is not type(b):
        return False
    if isinstance(a, float):
        return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)
    return a == b


def _mismatches(column, digits: int, seed: int) -> list:
    values = _numbers(digits, seed)
    ours = column(values, digits)
    assert len(ours) == len(values)
    rounded = [_num(v, digits) for v in values]
    return [(v, o, r) for v, o, r in zip(values, ours, rounded, strict=True) if not _same(o, r)]


def test_the_fast_rounding_is_rounds_float_for_every_number() -> None:
    for digits in DIGITS:
        for seed in range(2):  # about 860 000 numbers in all, over half of them at or next to a half
            assert _mismatches(_column, digits, seed) == [], digits


def test_the_check_catches_a_rounding_without_the_guard_near_a_half() -> None:
    spec = importlib.util.spec_from_file_location("replay_rounding_wrong", WRONG)
    wrong = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(wrong)
    assert wrong.column([0.00005], 4) != [_num(0.00005, 4)]  # 0.0 where round() gives 0.0001
    for digits in DIGITS:
        assert len(_mismatches(wrong.column, digits, 0)) > 100, digits
