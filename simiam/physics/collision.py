"""Body collision (`Physics.body_collision_detection`): any crossing of a base-plate edge with an obstacle
edge, touching included. A plate wholly inside an obstacle without an edge crossing is not a collision,
as in the original."""

from __future__ import annotations

from collections.abc import Sequence

from simiam.physics.precheck import centroid, precheck, span
from simiam.physics.segments import PolygonBox, Surface, Tolerance, crossing, culled_crossings, polygon_edges


def plate_collides_exact(plate: Sequence[Sequence[float]], obstacles: Sequence[Surface],
                         plate_span: float | None = None) -> bool:
    """The original's test on the original's vertices: for every obstacle that passes its precheck, every
    plate edge against every obstacle edge, no culling. `obstacles` are `ObstacleEdges.surfaces`;
    `plate_span` is the plate's span as the original computed it once (default: from these vertices)."""
    plate_span = span(plate) if plate_span is None else plate_span
    middle = centroid(plate)
    edges = polygon_edges(plate)
    for obstacle_edges, obstacle_middle, obstacle_span in obstacles:
        if not precheck(middle, plate_span, obstacle_middle, obstacle_span):
            continue
        for a in edges:
            for b in obstacle_edges:
                if crossing(a, b) is not None:
                    return True
    return False


def plate_collides(xs: Sequence[float], ys: Sequence[float], polygons: Sequence[PolygonBox],
                   margins: Tolerance | None = None) -> bool | None:
    """The same test for the plate's world vertices (xs, ys) against `polygons` (`ObstacleEdges.polygons`,
    or a superset of the candidates from `ObstacleEdges.near`), with bounding-box culling that only skips
    pairs whose padded boxes are apart: no real crossing is dropped.

    The answer holds for every plate within `margins`' slack of (xs, ys) in each coordinate (`margins` from
    segments.tolerance; default: these are the original's vertices); None when it might not
    (a vertex within rounding of an obstacle edge, say): then ask `plate_collides_exact` on the original's
    vertices. Near-collinear edges whose boxes are apart are simiam.physics.parallel's to find."""
    undecided = False
    for hit in culled_crossings(xs, ys, polygons, margins):
        if hit is not None:
            return True
        undecided = True
    return None if undecided else False
