"""Margins: how far each figure a scenario check judged is from its limit.

A scenario check compares figures of its runs with limits: the TRUE clearance to the obstacles with 0, the
arrival time with the run's length, the laps with 2, the turning rate with its cap. A verdict that a last
bit can flip is a figure sitting at its limit (issue 20: a week-6 wrong version skimmed the wall by 0 to
2 mm, so whether it "collided" depended on the BLAS kernel). So each scenario check records, for each
figure it judged, its run nearest the limit, in its result's details:

    details["margins"] = [{"figure": "clearance", "unit": "m", "limit": 0.0, "passes": "over",
                           "value": 0.0236, "margin": 0.0236, "run": "switching to (-1, 1)"}, ...]

`margin` is the distance from the limit in the figure's unit, positive on the passing side, negative on the
failing side; `value` (and `margin`) is None where the run never produced the figure (never arrived, never
settled, ended before it was measured), which fails. A clearance of 0 is a collision: how deep the robot
would have gone is not measured, so a collision's margin is 0, not a distance. `grade selfcheck` prints
them: how far the reference is from each limit, and how far each caught wrong version is on the failing
side.

A margin describes one run. It is not a bound on what a perturbation does: a closed loop that switches
between controllers (weeks 5 and 7) can turn a one-bit difference into another path. Those verdicts are
shown robust by grading under every BLAS kernel and from nudged starts (tests/grader/test_verdict_margins.py)
and, for hidden variants, by the instructor tools that keep only variants the reference passes from nudged
starts too.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Limit:
    """One figure a check judges: its name and unit, the limit, and which side passes (`above`: a value at
    or over the limit passes, else one at or under it; `strict`: the limit itself fails, as a clearance of
    0, touching, is a collision)."""

    figure: str
    unit: str
    limit: float
    above: bool
    strict: bool = False
    percent: bool = False  # a fraction (week 3's overshoot) that people read as a percentage: shown x 100


    def margin(self, value: float | None) -> float | None:
        """The signed distance of `value` from the limit, positive on the passing side (None: no value)."""
        if value is None:
            return None
        return value - self.limit if self.above else self.limit - value

    def entry(self, value: float | None, run: str) -> dict[str, Any]:
        out = {"figure": self.figure, "unit": self.unit, "limit": self.limit,
               "passes": ("over" if self.strict else "above") if self.above else
                         ("under" if self.strict else "below"),
               "value": value, "margin": self.margin(value), "run": run}
        if self.percent:
            out["shown"] = "percent"
        return out


# the TRUE gap between the base plate and the obstacles, at every step; 0 once they touch (a collision)
CLEARANCE = Limit("clearance", "m", 0.0, above=True, strict=True)


class Margins:
    """The figures of one check's runs, keeping per figure the run nearest its limit (or past it)."""

    def __init__(self) -> None:
        self._worst: dict[str, dict[str, Any]] = {}

    def add(self, limit: Limit, value: float | None, run: str) -> None:
        """One run's figure. A run without it (value None) is the worst there is."""
        entry = limit.entry(value, run)
        held = self._worst.get(limit.figure)
        if held is None or _below(entry["margin"], held["margin"]):
            self._worst[limit.figure] = entry

    def to_json(self) -> list[dict[str, Any]]:
        """The entries, in the order the figures were first added."""
        return list(self._worst.values())


def _below(a: float | None, b: float | None) -> bool:
    if a is None:
        return b is not None
    return b is not None and a < b


def passes(entry: dict[str, Any]) -> bool:
    """Whether the figure of a margins entry is on the passing side of its limit."""
    margin = entry.get("margin")
    if margin is None:
        return False
    return margin > 0 if entry.get("passes") in ("over", "under") else margin >= 0


_SIDES = {"above": ">=", "over": ">", "below": "<=", "under": "<"}


def words(entry: dict[str, Any]) -> str:
    """One margin for people: 'clearance 0.0236 m (limit > 0 m): 0.0236 m to spare [switching to (-1, 1)]'.
    Works on any dict of that shape (a result read back from JSON)."""
    unit = f" {entry['unit']}" if entry.get("unit") else ""
    value, margin, limit = entry.get("value"), entry.get("margin"), entry.get("limit")
    if entry.get("shown") == "percent":  # stored as fractions, read as the checks' messages say them
        unit = " %"
        value, margin, limit = (None if f is None else f * 100 for f in (value, margin, limit))
    shown = "none" if value is None else f"{value:.4g}{unit}"
    if margin is None:
        how = "the run ended without it"
    elif passes(entry):
        how = f"{margin:.3g}{unit} to spare"
    elif entry.get("figure") == CLEARANCE.figure and value == 0:
        how = "touching: a collision"
    elif margin == 0:
        how = "at the limit, which fails"
    else:
        how = f"{-margin:.3g}{unit} past it"
    side = _SIDES.get(str(entry.get("passes")), "?")
    run = f" [{entry['run']}]" if entry.get("run") else ""
    return f"{entry.get('figure')} {shown} (limit {side} {limit:g}{unit}): {how}{run}"
