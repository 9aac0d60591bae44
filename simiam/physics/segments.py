"""Edge-edge crossings as the original computed them (`Surface2D.intersection_with_surface`), and the
obstacle edge table the fast paths cull with.

For edge a = (x1, y1)-(x2, y2) and edge b = (x3, y3)-(x4, y4):
    u_a = (x43*y13 - y43*x13) / d,  u_b = (x21*y13 - y21*x13) / d,  d = y43*x21 - x43*y21
and they cross when both parameters lie in the closed interval [0, 1] (touching counts). Parallel edges
(d = 0) never cross, as in the original where the division gives Inf/NaN. The point is taken along a.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

# Bounding boxes are widened by this much before culling, so that rounding in the exact formula can never
# report a crossing the cull has thrown away (coordinates are metres, a few units at most).
CULL_PAD = 1e-9

Edge = tuple[float, float, float, float]
# (xmin, xmax, ymin, ymax, edge table) of one obstacle, boxes padded by CULL_PAD
PolygonBox = tuple[float, float, float, float, list[tuple[float, ...]]]


def crossing(a: Edge, b: Edge) -> float | None:
    """u_a of the crossing of edge a with edge b, or None; the original's formula and closed intervals."""
    x1, y1, x2, y2 = a
    x3, y3, x4, y4 = b
    y13 = y1 - y3
    x13 = x1 - x3
    x21 = x2 - x1
    y21 = y2 - y1
    x43 = x4 - x3
    y43 = y4 - y3
    d = y43 * x21 - x43 * y21
    if d == 0.0:
        return None
    ua = (x43 * y13 - y43 * x13) / d
    ub = (x21 * y13 - y21 * x13) / d
    if 0.0 <= ua <= 1.0 and 0.0 <= ub <= 1.0:
        return ua
    return None


def polygon_edges(points: Sequence[Sequence[float]]) -> list[Edge]:
    """The closed polygon's edges: vertex k to vertex k+1, the last back to the first."""
    n = len(points)
    return [(float(points[k][0]), float(points[k][1]), float(points[(k + 1) % n][0]),
             float(points[(k + 1) % n][1])) for k in range(n)]


class ObstacleEdges:
    """The obstacles' edges, precomputed for fast culled tests: per polygon a padded bounding box and, per
    edge, (x3, y3, x43, y43, xmin, xmax, ymin, ymax) with the edge's own padded box."""

    def __init__(self, obstacles: Sequence[Sequence[Sequence[float]]]) -> None:
        self.polygons: list[PolygonBox] = []
        self.edges: list[list[Edge]] = []
        for poly in obstacles:
            edges = polygon_edges(poly)
            self.edges.append(edges)
            table: list[tuple[float, ...]] = []
            for x3, y3, x4, y4 in edges:
                table.append((x3, y3, x4 - x3, y4 - y3, min(x3, x4) - CULL_PAD, max(x3, x4) + CULL_PAD,
                              min(y3, y4) - CULL_PAD, max(y3, y4) + CULL_PAD))
            xs = [p[0] for p in edges]
            ys = [p[1] for p in edges]
            self.polygons.append((min(xs) - CULL_PAD, max(xs) + CULL_PAD, min(ys) - CULL_PAD,
                                  max(ys) + CULL_PAD, table))

    def near(self, x: float, y: float, reach: float) -> list[PolygonBox]:
        """The obstacles whose padded box meets the square of half-side `reach` around (x, y): everything
        a body lying within `reach` of (x, y) could touch."""
        return [p for p in self.polygons
                if not (x + reach < p[0] or x - reach > p[1] or y + reach < p[2] or y - reach > p[3])]


def culled_crossings(xs: Sequence[float], ys: Sequence[float],
                     polygons: Sequence[PolygonBox]) -> Iterator[tuple[float, float]]:
    """The crossing points (taken along the polygon's edge, as `crossing` does) of the closed polygon with
    world vertices (xs, ys) against `polygons`, with bounding-box culling that only skips pairs whose padded
    boxes are apart, so no real crossing is dropped. This is the hot loop of every step: it is written out
    flat for speed, and callers stop it at the first point when that is all they need."""
    pxmin = min(xs)
    pxmax = max(xs)
    pymin = min(ys)
    pymax = max(ys)
    n = len(xs)
    for oxmin, oxmax, oymin, oymax, table in polygons:
        if pxmax < oxmin or pxmin > oxmax or pymax < oymin or pymin > oymax:
            continue
        # only the obstacle edges whose box meets the polygon's box can cross one of its edges
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
                    yield x1 + x21 * ua, y1 + y21 * ua
