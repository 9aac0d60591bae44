"""The QuickBot IR sensor model: the cone polygon and the distance -> voltage -> ADC ("raw") map.

The voltage curve is the original's `polyfit(table_d, table_V, 5)` (weeks 3-7). Week 2 uses the manual's
divider (raw = V*1000/2) on the same true curve, as the contract says (the original's week-2 polynomial
contradicts its own table).
"""

from __future__ import annotations

import functools
import math

from simiam.physics.transform import transform_point
from simiam.robot.rounding import round_half_away

Point = tuple[float, float]

# V(d), highest power first as MATLAB's polyval takes them: polyfit(table_d, table_V, 5) of the original.
VOLTAGE_COEFFS = (-10749.324, 10994.428, -4448.079, 906.570, -98.411, 5.496)


def ir_voltage(d: float) -> float:
    """Sensor output voltage at distance d (m), by Horner's rule as MATLAB's polyval evaluates it."""
    v = 0.0
    for c in VOLTAGE_COEFFS:
        v = v * d + c
    return v


# A bound on |d raw_units / d distance| over the sensor's range (up to 0.31 m): the derivative's terms
# bounded one by one, times the larger divider (500 per volt, week 2).
RAW_SLOPE = 500 * sum(k * abs(c) * 0.31 ** (k - 1) for k, c in enumerate(reversed(VOLTAGE_COEFFS)) if k)


def _adc(d: float, ir_mode: str) -> tuple[float, int, int]:
    """The ADC's input for distance d (unrounded) and its clamp (lo, hi), per ir_mode."""
    v = ir_voltage(d)
    if ir_mode == "week3":
        return v * 1000 / 3, 133, 917  # the original writes V*1000/3 (left to right)
    if ir_mode == "week2":
        return v * 1000 / 2, 200, 1375
    raise ValueError(f"unknown ir_mode {ir_mode!r} (expected 'week2' or 'week3')")


def distance_to_raw(d: float, ir_mode: str = "week3") -> int:
    """`QuickBot.ir_distance_to_raw`: distance (m) -> ADC value, round half away from zero, clamped."""
    x, lo, hi = _adc(d, ir_mode)
    return min(max(round_half_away(x), lo), hi)


def settled_raw(d: float, error: float, ir_mode: str = "week3") -> int | None:
    """d's raw value if every distance within `error` of d gives it, else None: the ADC's input must be
    farther from a rounding boundary (an integer plus one half) than the distances can move it. Polynomial
    rounding, which differs between two nearby distances by far less than 1e-9 raw units, is counted in."""
    x, lo, hi = _adc(d, ir_mode)
    if error and abs(x - math.floor(x) - 0.5) <= RAW_SLOPE * error + 1e-9:
        return None
    return min(max(round_half_away(x), lo), hi)


def cone_polygon(r: float, spread: float) -> tuple[Point, ...]:
    """The 6-vertex cone of range r in the sensor frame: apex, then five far points on the circle r."""
    r1 = r * math.tan(spread / 4)
    r2 = r * math.tan(spread / 2)
    a1 = math.sqrt(r * r - r1 * r1)
    a2 = math.sqrt(r * r - r2 * r2)
    return ((0.0, 0.0), (a2, r2), (a1, r1), (r, 0.0), (a1, -r1), (a2, -r2))


@functools.lru_cache(maxsize=64)
def mounted_cone(mount: tuple[float, float, float], r: float, spread: float) -> tuple[Point, ...]:
    """The cone of range r in the robot frame: the sensor-frame cone moved by T(mount), as the original
    stores it (apex first, so the apex is the sensor position)."""
    return tuple(transform_point(mount, px, py) for px, py in cone_polygon(r, spread))
