"""How far the robot kept from the obstacle it drove its laps around (week 6), from its TRUE positions.

The laps themselves are counted at the week's gate by simiam.laps (`simiam run` prints them too); this
module holds the grader's other lap figure, the median distance to the obstacle, which needs the
grader's point-to-segment distance (grader.clearance).
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence

from grader.clearance import point_to_segment

Point = tuple[float, float]


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
