"""Body collision (`Physics.body_collision_detection`): any crossing of a base-plate edge with an obstacle
edge, touching included. A plate wholly inside an obstacle without an edge crossing is not a collision,
as in the original."""

from __future__ import annotations

from collections.abc import Sequence

from simiam.physics.segments import ObstacleEdges, PolygonBox, crossing, polygon_edges


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
    pxmin = min(xs)
    pxmax = max(xs)
    pymin = min(ys)
    pymax = max(ys)
    n = len(xs)
    for oxmin, oxmax, oymin, oymax, table in polygons:
        if pxmax < oxmin or pxmin > oxmax or pymax < oymin or pymin > oymax:
            continue
        # only the obstacle edges whose box meets the plate's box can cross a plate edge
        table = [e for e in table if not (pxmax < e[4] or pxmin > e[5] or pymax < e[6] or pymin > e[7])]
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
                if 0.0 <= ub <= 1.0:
                    return True
    return False
