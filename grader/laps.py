"""Laps around an obstacle, counted at a gate, and how far the robot kept from the obstacle (week 6).

The original test counted a lap each time the robot left a 0.1 m disc around the start: a robot that
wobbles on the disc's edge counts laps it never drove, and one that passes 0.11 m from its start counts
none. Here a lap is a crossing of a GATE, a segment from the obstacle to the arena wall, in the running
direction; a crossing back takes one away. The net count is how many times the path wound around the
obstacle, whatever the robot does near the gate. All from the simulator's TRUE positions.
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence
from dataclasses import dataclass

from grader.clearance import point_to_segment

Point = tuple[float, float]


@dataclass(frozen=True)
class Gate:
    """The segment x = `x`, y in [y_low, y_high]; `sign` +1 if the running direction crosses it toward
    larger x, -1 toward smaller x."""

    x: float
    y_low: float
    y_high: float
    sign: int

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


def distance_to(point: Point, obstacles: Sequence[Sequence[Point]]) -> float:
    """The distance from a point to the nearest edge of the obstacles (the robot's centre to the wall)."""
    return min(
        point_to_segment(point, poly[k], poly[(k + 1) % len(poly)])
        for poly in obstacles
        for k in range(len(poly))
    )


def median_distance(
    xs: Sequence[float], ys: Sequence[float], obstacles: Sequence[Sequence[Point]], every: int = 5
) -> float:
    """The median distance from the robot's centre to the obstacles over the positions given (every
    `every`-th, enough for a median at 7.5 mm per step)."""
    return statistics.median(distance_to((xs[k], ys[k]), obstacles) for k in range(0, len(xs), every))
