"""Laps around an obstacle, counted at a gate: what `simiam run` prints and what `grade` judges (week 6).

The original test counted a lap each time the robot left a 0.1 m disc around the start: a robot that
wobbles on the disc's edge counts laps it never drove, and one that passes 0.11 m from its start counts
none (tests/grader/test_laps.py keeps that counter as the wrong version). Here a lap is a crossing of a
GATE, a segment from the obstacle to the arena wall, in the running direction; a crossing back takes one
away. The net count is how many times the path wound around the obstacle, whatever the robot does near
the gate. A week declares its gate (`Week.lap_gate`); the counts use the simulator's TRUE positions.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

Point = tuple[float, float]


class _Segment(NamedTuple):
    x: float
    y_low: float
    y_high: float
    sign: int


class Gate(_Segment):
    """The segment x = `x`, y in [y_low, y_high]; `sign` +1 if the running direction crosses it toward
    larger x, -1 toward smaller x. Immutable; checked when made. (A NamedTuple rather than a frozen
    dataclass, as LapCount below: week 6's declaration, which the sandbox worker imports on every start,
    builds one, and a dataclass costs about a millisecond to create.)"""

    __slots__ = ()

    def __new__(cls, x: float, y_low: float, y_high: float, sign: int) -> Gate:
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in (x, y_low, y_high)):
            raise ValueError(f"Gate: x, y_low and y_high must be finite numbers, got {(x, y_low, y_high)!r}")
        if not y_low < y_high:
            raise ValueError(f"Gate: y_low must be below y_high, got {y_low} and {y_high}")
        if sign not in (1, -1) or isinstance(sign, bool):
            raise ValueError(f"Gate: sign must be +1 (toward larger x) or -1, got {sign!r}")
        return super().__new__(cls, x, y_low, y_high, sign)

    def reversed(self) -> Gate:
        """The same segment with the other running direction (the robot going round the other way)."""
        return Gate(self.x, self.y_low, self.y_high, -self.sign)

    def words(self) -> str:
        """Where the gate is and which way a lap crosses it, for people."""
        toward = "+x" if self.sign > 0 else "-x"
        return f"x = {self.x:g} from y = {self.y_low:g} to {self.y_high:g}, crossed toward {toward}"

    def crossing(self, a: Point, b: Point) -> int:
        """+1 if the step from a to b crosses the gate in the running direction, -1 against it, else 0.

        A point exactly on the gate's line counts as past it: a robot that starts on the gate and drives
        on has not crossed it; one that backs off first has crossed it backwards (-1), and its driving
        forward again gives that back (+1)."""
        side_a = self.sign * (a[0] - self.x)
        side_b = self.sign * (b[0] - self.x)
        if side_a < 0 <= side_b:
            direction = 1
        elif side_b < 0 <= side_a:
            direction = -1
        else:
            return 0
        t = (self.x - a[0]) / (b[0] - a[0]) if b[0] != a[0] else 0.0
        y = a[1] + t * (b[1] - a[1])
        return direction if self.y_low <= y <= self.y_high else 0


def laps(xs: Sequence[float], ys: Sequence[float], gate: Gate) -> list[int]:
    """The net number of laps after each step (index k: after the step from position k-1 to k)."""
    count = 0
    out = [0]
    for k in range(1, len(xs)):
        count += gate.crossing((xs[k - 1], ys[k - 1]), (xs[k], ys[k]))
        out.append(count)
    return out


class LapsDone:
    """A run's stop rule: true once the net count through `gate` reaches `n`, fed the TRUE position after
    each step (the simulator's `until`, called with each StepRecord). Counts as `laps` does on the run's
    trace from `start`, so the step it stops at is the one where that list first reaches `n`: the original
    test ended there too ("the loop breaks at that moment")."""

    def __init__(self, gate: Gate, n: int, start: Point) -> None:
        self.gate, self.n = gate, n
        self.count = 0
        self._last = (start[0], start[1])

    def __call__(self, record: Any) -> bool:  # a simiam.simulator.StepRecord
        here = (record.pose[0], record.pose[1])
        self.count += self.gate.crossing(self._last, here)
        self._last = here
        return self.count >= self.n


class LapCount(NamedTuple):
    """The laps of one run through a gate: `gate` (as declared, or reversed when the robot went round the
    other way), `done` the most laps completed at any time, `times` when each of them was first done (s)."""

    gate: Gate
    done: int
    times: tuple[float, ...]

    def words(self) -> str:
        """One line for `simiam run`'s summary."""
        text = f"Laps: {self.done} through the gate ({self.gate.words()})"
        if len(self.times) == 1:
            text += f", completed at t = {self.times[0]:.2f} s"
        elif self.times:
            first, last = self.times[0], self.times[-1]
            text += f", the first completed at t = {first:.2f} s, the last at t = {last:.2f} s"
        return text + "."


def count_laps(xs: Sequence[float], ys: Sequence[float], ts: Sequence[float], gate: Gate) -> LapCount:
    """The laps of a run through `gate`, in whichever direction the robot went round more often: a
    student's own run may follow the wall on either side (week 6's `fw_direction`)."""
    best = None
    for way in (gate, gate.reversed()):
        counted = laps(xs, ys, way)
        done = max(counted)
        if best is None or done > best.done:
            times = tuple(ts[counted.index(n)] for n in range(1, done + 1))
            best = LapCount(way, done, times)
    assert best is not None
    return best
