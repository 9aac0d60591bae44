"""The gap between the robot's base plate and the obstacles, in pure Python.

Shapely's `Polygon.distance` gave this before; importing it (and numpy, which it imports) cost the
grading process 0.1-0.25 s of CPU for a metric that needs a few hundred segment distances
(docs/performance.md). This follows GEOS's algorithm for polygons: 0 when they overlap or touch (an
edge of one crosses an edge of the other, or one lies inside the other), else the smallest distance
from an edge's end point to an edge of the other polygon, computed as GEOS computes it
(`Distance::pointToSegment`), so the figures agree with shapely's (tests/grader/test_clearance.py).
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Sequence

Point = tuple[float, float]
Box = tuple[float, float, float, float]  # xmin, xmax, ymin, ymax


# A gap found this much (m) beyond the smallest one so far may be skipped: far above the rounding of the
# bound (~1e-16 m) and far below anything measured, so the minimum found is bit-identical.
SLACK = 1e-9


class Shape:
    """A closed polygon's vertices, edges and bounding box."""

    def __init__(self, points: Sequence[Sequence[float]]) -> None:
        self.points: list[Point] = [(float(x), float(y)) for x, y in points]
        n = len(self.points)
        self.edges = [(self.points[k], self.points[(k + 1) % n]) for k in range(n)]
        xs = [p[0] for p in self.points]
        ys = [p[1] for p in self.points]
        self.box: Box = (min(xs), max(xs), min(ys), max(ys))
        self._segments: list[tuple] | None = None

    @property
    def segments(self) -> list[tuple]:
        """Per edge, what point_to_segment computes from it (the same floats), and its box."""
        if self._segments is None:
            out = []
            sqrt = math.sqrt
            for a, b in self.edges:
                (ax, ay), (bx, by) = a, b
                dx, dy = bx - ax, by - ay
                len2 = dx * dx + dy * dy
                # (min and max as the builtins pick: the first of equal values)
                out.append((ax, ay, bx, by, dx, dy, len2, sqrt(len2), a == b, bx if bx < ax else ax,
                            bx if bx > ax else ax, by if by < ay else ay, by if by > ay else ay))
            self._segments = out
        return self._segments


def directions(shapes: Sequence[Shape], most: int = 4) -> list[tuple[float, float]]:
    """Unit directions along which to bound the gaps (pose_bounds): the directions of the obstacles'
    edges, the commonest first, at most `most` of them (an axis-aligned world has two, x and y; a world
    turned by 45 degrees the two turned ones; any direction gives a true bound, these give tight ones)."""
    count: dict[int, int] = {}
    for shape in shapes:
        for a, b in shape.edges:
            if a != b:  # in thousandths of a radian: walls a hair off square count as square
                along = complex(*b) - complex(*a)
                mrad = round(cmath.phase(along) % math.pi * 1000) % round(math.pi * 1000)
                count[mrad] = count.get(mrad, 0) + 1
    ranked = sorted(count, key=lambda a: (-count[a], a))[:most] or [0, round(math.pi * 500)]
    return [(math.cos(a / 1000), math.sin(a / 1000)) for a in ranked]


def pose_bounds(plate: Sequence[Sequence[float]], poses: Sequence[Sequence[float]],
                shapes: Sequence[Shape]) -> list[float]:
    """Per pose (x, y, theta), a lower bound of the gap between the plate placed there and the nearest of
    the shapes (negative where they may overlap): along each of a few directions (`directions`), how far
    apart the shape's extent and that of the plate's own box turned by theta (which holds the placed
    plate) lie. The plate's extent is widened by far more than the rounding of the placement and of these
    sums (transform's fast_error), so that no pose is ever bounded above its gap as computed. Cheap (no
    placement, no Shape): min_clearance measures only the poses whose bound can beat the smallest gap."""
    if not shapes:
        return [math.inf] * len(poses)
    bx, by = [float(p[0]) for p in plate], [float(p[1]) for p in plate]
    cx, cy = (min(bx) + max(bx)) / 2, (min(by) + max(by)) / 2
    hx, hy = (max(bx) - min(bx)) / 2, (max(by) - min(by)) / 2
    reach = max(abs(v) for v in bx + by)
    scale = max((abs(v) for shape in shapes for v in shape.box), default=0.0)
    cos, sin = math.cos, math.sin
    cs = [(cos(th), sin(th)) for _, _, th in poses]
    centres = [(c * cx - s * cy + x, s * cx + c * cy + y, 2.0 ** -44 * (reach + abs(x) + abs(y) + scale))
               for (x, y, _), (c, s) in zip(poses, cs, strict=True)]
    per_shape: list[list[float]] = [[-math.inf] * len(poses) for _ in shapes]
    for dx, dy in directions(shapes):
        # the plate's extent along (dx, dy): its centre's projection -+ its half-width there
        proj = [dx * px + dy * py for px, py, _ in centres]
        half = [hx * abs(dx * c + dy * s) + hy * abs(dy * c - dx * s) + err
                for (c, s), (_, _, err) in zip(cs, centres, strict=True)]
        low = [p - h for p, h in zip(proj, half, strict=True)]
        high = [p + h for p, h in zip(proj, half, strict=True)]
        for k, shape in enumerate(shapes):
            along = [dx * x + dy * y for x, y in shape.points]
            lo, hi = min(along), max(along)
            # the gap along this direction: the plate beyond the shape or short of it (negative: overlap);
            # the gap between them is at least the largest of these over the directions (the conditional
            # expressions are max(), three times faster)
            per_shape[k] = [(a if a > g else g) if (a := u - hi) > (b := lo - v) else (b if b > g else g)
                            for u, v, g in zip(low, high, per_shape[k], strict=True)]
    return list(map(min, *per_shape)) if len(per_shape) > 1 else per_shape[0]


def box_gap(a: Box, b: Box) -> float:
    """A lower bound of the distance between two shapes: the distance between their boxes."""
    dx = max(a[0] - b[1], b[0] - a[1], 0.0)
    dy = max(a[2] - b[3], b[2] - a[3], 0.0)
    return math.sqrt(dx * dx + dy * dy)


def distance(a: Shape, b: Shape) -> float:
    """The distance between two polygons (0 when they overlap or touch), as shapely's."""
    return nearer(a, b, math.inf)


def nearer(a: Shape, b: Shape, bound: float) -> float:
    """min(bound, distance(a, b)), bit for bit, with less work: polygons whose boxes are apart can
    neither cross nor contain each other, and a vertex whose box gap to an edge already exceeds the
    smallest distance so far is not measured against it (the scenarios' min_clearance passes the
    smallest gap of the run so far as `bound`)."""
    if box_gap(a.box, b.box) == 0.0:  # the boxes meet: the polygons may overlap or touch
        if any(_crosses(e, f) for e, f in _edge_pairs_that_may_meet(a, b)):
            return 0.0
        if _inside(a.points[0], b) or _inside(b.points[0], a):
            return 0.0
    # every end point of an edge is a vertex: each vertex of one against each edge of the other
    return _vertices_to_edges(b.points, a.segments, _vertices_to_edges(a.points, b.segments, bound))


def _edge_pairs_that_may_meet(a: Shape, b: Shape) -> list[tuple]:
    """The pairs of edges whose boxes meet: only those can cross or touch."""
    out = []
    for e, (*_, ex0, ex1, ey0, ey1) in zip(a.edges, a.segments, strict=True):
        for f, (*_, fx0, fx1, fy0, fy1) in zip(b.edges, b.segments, strict=True):
            if ex0 <= fx1 and fx0 <= ex1 and ey0 <= fy1 and fy0 <= ey1:
                out.append((e, f))
    return out


def nearest_edge(point: Point, segments: list[tuple]) -> float:
    """The smallest point_to_segment from `point` to the edges (Shape.segments), bit for bit, edges whose
    box is already farther than the nearest so far skipped."""
    return _vertices_to_edges([point], segments, math.inf)


def _vertices_to_edges(points: list[Point], segments: list[tuple], best: float) -> float:
    """min(best, point_to_segment of every point against every segment), skipping the pairs that
    cannot be nearer than the best so far (their box gap, a lower bound, exceeds it by SLACK)."""
    sqrt = math.sqrt
    for px, py in points:
        for ax, ay, bx, by, dx, dy, len2, length, degenerate, x0, x1, y0, y1 in segments:
            ex = x0 - px if px < x0 else px - x1 if px > x1 else 0.0
            ey = y0 - py if py < y0 else py - y1 if py > y1 else 0.0
            if (ex if ex > ey else ey) > best + SLACK:
                continue
            # point_to_segment, inline (the same operations in the same order)
            if degenerate:
                qx, qy = px - ax, py - ay
                d = sqrt(qx * qx + qy * qy)
            else:
                r = ((px - ax) * dx + (py - ay) * dy) / len2
                if r <= 0.0:
                    qx, qy = px - ax, py - ay
                    d = sqrt(qx * qx + qy * qy)
                elif r >= 1.0:
                    qx, qy = px - bx, py - by
                    d = sqrt(qx * qx + qy * qy)
                else:
                    d = abs(((ay - py) * dx - (ax - px) * dy) / len2) * length
            if d < best:
                best = d
    return best


def point_to_segment(p: Point, a: Point, b: Point) -> float:
    """GEOS's Distance::pointToSegment."""
    if a == b:
        return _point_distance(p, a)
    dx, dy = b[0] - a[0], b[1] - a[1]
    len2 = dx * dx + dy * dy
    r = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2
    if r <= 0.0:
        return _point_distance(p, a)
    if r >= 1.0:
        return _point_distance(p, b)
    s = ((a[1] - p[1]) * dx - (a[0] - p[0]) * dy) / len2
    return abs(s) * math.sqrt(len2)


def _point_distance(p: Point, q: Point) -> float:
    dx, dy = p[0] - q[0], p[1] - q[1]
    return math.sqrt(dx * dx + dy * dy)


def _orientation(p: Point, q: Point, r: Point) -> float:
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])


def _on_box(p: Point, q: Point, r: Point) -> bool:
    """r lies within the box of segment p-q (for a collinear r)."""
    return min(p[0], q[0]) <= r[0] <= max(p[0], q[0]) and min(p[1], q[1]) <= r[1] <= max(p[1], q[1])


def _crosses(e: tuple[Point, Point], f: tuple[Point, Point]) -> bool:
    """The segments meet (crossing or touching)."""
    p, q = e
    r, s = f
    d1, d2 = _orientation(r, s, p), _orientation(r, s, q)
    d3, d4 = _orientation(p, q, r), _orientation(p, q, s)
    if ((d1 > 0 > d2) or (d1 < 0 < d2)) and ((d3 > 0 > d4) or (d3 < 0 < d4)):
        return True
    return ((d1 == 0 and _on_box(r, s, p)) or (d2 == 0 and _on_box(r, s, q))
            or (d3 == 0 and _on_box(p, q, r)) or (d4 == 0 and _on_box(p, q, s)))


def _inside(p: Point, shape: Shape) -> bool:
    """p is inside the polygon (even-odd rule; the boundary is handled by _crosses)."""
    x, y = p
    inside = False
    for (x1, y1), (x2, y2) in shape.edges:
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside
