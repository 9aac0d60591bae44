"""IR ranging (`Physics.proximity_sensor_detection`): the nearest crossing of the sensor cone's edges with
obstacle edges, measured from the cone's apex, each distance clamped to [min_range, max_range].
Nothing found (or everything at or beyond max_range) reads max_range. An obstacle wholly inside the cone
without an edge crossing is not seen, as in the original."""

from __future__ import annotations

import math
from collections.abc import Sequence

from simiam.physics.segments import ObstacleEdges, PolygonBox, crossing, polygon_edges


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
    cxmin = min(xs)
    cxmax = max(xs)
    cymin = min(ys)
    cymax = max(ys)
    ax = xs[0]
    ay = ys[0]
    n = len(xs)
    d_min = max_range
    for oxmin, oxmax, oymin, oymax, table in polygons:
        if cxmax < oxmin or cxmin > oxmax or cymax < oymin or cymin > oymax:
            continue
        # only the obstacle edges whose box meets the cone's box can cross a cone edge
        table = [e for e in table if not (cxmax < e[4] or cxmin > e[5] or cymax < e[6] or cymin > e[7])]
        if not table:
            continue
        for k in range(n):
            x1 = xs[k]
            y1 = ys[k]
            x2 = xs[k + 1 - n]
            y2 = ys[k + 1 - n]
            if x1 < x2:
                axmin, axmax = x1, x2
            else:
                axmin, axmax = x2, x1
            if y1 < y2:
                aymin, aymax = y1, y2
            else:
                aymin, aymax = y2, y1
            x21 = x2 - x1
            y21 = y2 - y1
            for x3, y3, x43, y43, exmin, exmax, eymin, eymax in table:
                if axmax < exmin or axmin > exmax or aymax < eymin or aymin > eymax:
                    continue
                d = y43 * x21 - x43 * y21
                if d == 0.0:
                    continue
                y13 = y1 - y3
                x13 = x1 - x3
                ua = (x43 * y13 - y43 * x13) / d
                if ua < 0.0 or ua > 1.0:
                    continue
                ub = (x21 * y13 - y21 * x13) / d
                if ub < 0.0 or ub > 1.0:
                    continue
                px = x1 + x21 * ua
                py = y1 + y21 * ua
                r = math.sqrt((px - ax) ** 2 + (py - ay) ** 2)
                if r < min_range:
                    r = min_range
                if r < d_min:
                    d_min = r
    return d_min
