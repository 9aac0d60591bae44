"""IR ranging (`Physics.proximity_sensor_detection`): the nearest crossing of the sensor cone's edges with
obstacle edges, measured from the cone's apex, each distance clamped to [min_range, max_range].
Nothing found (or everything at or beyond max_range) reads max_range. An obstacle wholly inside the cone
without an edge crossing is not seen, as in the original."""

from __future__ import annotations

import math
from collections.abc import Sequence

from simiam.physics.precheck import centroid, precheck, span
from simiam.physics.segments import PolygonBox, Surface, Tolerance, crossing, culled_crossings, polygon_edges


def cone_range_exact(cone: Sequence[Sequence[float]], obstacles: Sequence[Surface], min_range: float,
                     max_range: float, cone_span: float | None = None) -> float:
    """The original's ranging on the original's vertices: for every obstacle that passes its precheck,
    every cone edge against every obstacle edge, no culling. `cone` is the 6-vertex cone in world
    coordinates, apex first; `obstacles` are `ObstacleEdges.surfaces`; `cone_span` is the cone's span as
    the original computed it once (default: from these vertices)."""
    cone_span = span(cone) if cone_span is None else cone_span
    middle = centroid(cone)
    ax, ay = cone[0]
    d_min = max_range
    edges = polygon_edges(cone)
    for obstacle_edges, obstacle_middle, obstacle_span in obstacles:
        if not precheck(middle, cone_span, obstacle_middle, obstacle_span):
            continue
        for a in edges:
            for b in obstacle_edges:
                ua = crossing(a, b)
                if ua is None:
                    continue
                px = a[0] + (a[2] - a[0]) * ua
                py = a[1] + (a[3] - a[1]) * ua
                d = min(max(math.sqrt((px - ax) ** 2 + (py - ay) ** 2), min_range), max_range)
                d_min = min(d_min, d)
    return d_min


def cone_range(xs: Sequence[float], ys: Sequence[float], polygons: Sequence[PolygonBox],
               min_range: float, max_range: float, margins: Tolerance | None = None,
               box: tuple[float, float, float, float] | None = None) -> tuple[float, float] | None:
    """`cone_range_exact` for the cone's world vertices (xs, ys; apex first) against `polygons`
    (`ObstacleEdges.polygons` or the candidates from `ObstacleEdges.near`), with bounding-box culling that
    only skips pairs whose padded boxes are apart.

    Returns (range, error): for every cone within `margins`' slack of (xs, ys) in each coordinate (`margins`
    from segments.tolerance; default: these are the original's vertices) the original's
    test finds the same crossings, and its range lies within `error` of this one; None when some crossing
    might be found or lost (then ask `cone_range_exact` on the original's vertices). Near-collinear edges
    whose boxes are apart are simiam.physics.parallel's to find. `box`: a box holding the vertices, if
    known (segments.culled_crossings)."""
    ax = xs[0]
    ay = ys[0]
    d_min = max_range
    error = 0.0
    for hit in culled_crossings(xs, ys, polygons, margins, box):
        if hit is None:
            return None
        px, py, e = hit
        r = math.sqrt((px - ax) ** 2 + (py - ay) ** 2)
        if r < min_range:
            r = min_range
        if r < d_min:
            d_min = r
        if e > error:
            error = e
    if not error:  # nothing crossed: max_range whatever the vertices
        return d_min, 0.0
    # the apex moves by the slack in each coordinate; the squares and square root round in both evaluations
    return d_min, error + 2 * (margins[0] if margins else 0.0) + 1e-15
