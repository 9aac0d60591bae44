"""Body collision (`Physics.body_collision_detection`): any crossing of a base-plate edge with an obstacle
edge, touching included. A plate wholly inside an obstacle without an edge crossing is not a collision,
as in the original."""

from __future__ import annotations

from collections.abc import Sequence

from simiam.physics.segments import ObstacleEdges, PolygonBox, crossing, culled_crossings, polygon_edges


def plate_collides_exact(plate: Sequence[Sequence[float]], obstacles: ObstacleEdges) -> bool:
    """Every plate edge against every obstacle edge, no culling: the reference the fast path is tested on."""
    for a in polygon_edges(plate):
        for edges in obstacles.edges:
            for b in edges:
                if crossing(a, b) is not None:
                    return True
    return False


def plate_collides(xs: Sequence[float], ys: Sequence[float], polygons: Sequence[PolygonBox]) -> bool:
    """The same test as `plate_collides_exact` for the plate's world vertices (xs, ys) against `polygons`
    (`ObstacleEdges.polygons`, or a superset of the candidates from `ObstacleEdges.near`), with
    bounding-box culling that only skips pairs whose padded boxes are apart: no real crossing is dropped."""
    for _ in culled_crossings(xs, ys, polygons):
        return True
    return False
