"""IR ranging (`Physics.proximity_sensor_detection`): the nearest crossing of the sensor cone's edges with
obstacle edges, measured from the cone's apex, each distance clamped to [min_range, max_range].
Nothing found (or everything at or beyond max_range) reads max_range. An obstacle wholly inside the cone
without an edge crossing is not seen, as in the original."""

from __future__ import annotations

import math
from collections.abc import Sequence

from simiam.physics.segments import ObstacleEdges, PolygonBox, crossing, culled_crossings, polygon_edges


def cone_range_exact(cone: Sequence[Sequence[float]], obstacles: ObstacleEdges,
                     min_range: float, max_range: float) -> float:
    """Every cone edge against every obstacle edge, no culling: the reference for `cone_range`.
    `cone` is the 6-vertex cone in world coordinates, apex first."""
    ax, ay = cone[0]
    d_min = max_range
    for a in polygon_edges(cone):
        for edges in obstacles.edges:
            for b in edges:
                ua = crossing(a, b)
                if ua is None:
                    continue
                px = a[0] + (a[2] - a[0]) * ua
                py = a[1] + (a[3] - a[1]) * ua
                d = min(max(math.sqrt((px - ax) ** 2 + (py - ay) ** 2), min_range), max_range)
                d_min = min(d_min, d)
    return d_min


def cone_range(xs: Sequence[float], ys: Sequence[float], polygons: Sequence[PolygonBox],
               min_range: float, max_range: float) -> float:
    """`cone_range_exact` for the cone's world vertices (xs, ys; apex first) against `polygons`
    (`ObstacleEdges.polygons` or the candidates from `ObstacleEdges.near`), with bounding-box culling that
    only skips pairs whose padded boxes are apart."""
    ax = xs[0]
    ay = ys[0]
    d_min = max_range
    for px, py in culled_crossings(xs, ys, polygons):
        r = math.sqrt((px - ax) ** 2 + (py - ay) ** 2)
        if r < min_range:
            r = min_range
        if r < d_min:
            d_min = r
    return d_min
