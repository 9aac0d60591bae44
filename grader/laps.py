"""How the robot drove its laps around the obstacle (week 6), from its TRUE poses.

The laps themselves are counted at the week's gate by simiam.laps (`simiam run` prints them too); this
module holds the grader's other lap figures: the median distance to the obstacle, which needs the grader's
point-to-segment distance (grader.clearance), and the turning rate, which tells a robot driving along the
wall from one zig-zagging across d_fw.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Sequence

from grader.clearance import Shape, nearest_edge, point_to_segment

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
    `every`-th, enough for a median at 7.5 mm per step). Each is distance_to's, bit for bit: the same
    point_to_segment arithmetic (clearance's inline one), edges whose box is already farther than the
    nearest found skipped (tests/grader/test_laps.py)."""
    edges = [segment for poly in obstacles for segment in Shape(poly).segments]
    return statistics.median(nearest_edge((xs[k], ys[k]), edges) for k in range(0, len(xs), every))


def turning_rate(thetas: Sequence[float], dt: float) -> float | None:
    """How fast the robot turned on average (rad/s): the mean of |theta_{k+1} - theta_k| (each difference
    wrapped into [-pi, pi]) over dt. Following a wall, a robot turns at the corners; one steered only toward
    the line at d_fw (week 6's u_fw without its tangent) swings across it all the time, several times faster.
    None for fewer than two headings."""
    if len(thetas) < 2:
        return None
    pairs = zip(thetas, thetas[1:], strict=False)
    turned = sum(abs(math.atan2(math.sin(b - a), math.cos(b - a))) for a, b in pairs)
    return turned / ((len(thetas) - 1) * dt)
