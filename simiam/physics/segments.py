"""Edge-edge crossings as the original computed them (`Surface2D.intersection_with_surface`), and the
obstacle edge table the fast paths cull with.

For edge a = (x1, y1)-(x2, y2) and edge b = (x3, y3)-(x4, y4):
    u_a = (x43*y13 - y43*x13) / d,  u_b = (x21*y13 - y21*x13) / d,  d = y43*x21 - x43*y21
and they cross when both parameters lie in the closed interval [0, 1] (touching counts). Parallel edges
(d = 0) never cross, as in the original where the division gives Inf/NaN. The point is taken along a.

The fast loop (`culled_crossings`) works on the robot's vertices as `transform_fast` places them, which
may differ from the original's by `slack` in each coordinate (transform.fast_error). It decides a pair only
where no vertices within `slack` of these, evaluated by the same formula, could decide it the other way,
and reports the others as undecided (None): then the caller asks the exact path, on the original's
vertices. Pairs whose boxes are apart are skipped; the formula can still report such a pair when the two
edges are nearly collinear (its rounding, not their geometry), which simiam.physics.parallel looks out for.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from simiam.physics.precheck import centroid, span

# Bounding boxes are widened by this much before culling, so that rounding in the exact formula can never
# report a real crossing the cull has thrown away (coordinates are metres, a few units at most). Culled
# pairs are therefore always at least CULL_PAD apart, which bounds how parallel two edges the formula still
# reports must be (simiam.physics.parallel).
CULL_PAD = 1e-9

U = 2.0 ** -53  # the unit roundoff of a double

Edge = tuple[float, float, float, float]
# (xmin, xmax, ymin, ymax, edge table) of one obstacle, boxes padded by CULL_PAD
PolygonBox = tuple[float, float, float, float, list[tuple[float, ...]]]
# what the original's precheck and all-pairs test read of one obstacle: its edges, centroid and span
Surface = tuple[list[Edge], tuple[float, float], float]
# a crossing point the fast loop decided, and how far (Euclidean) the original's point may lie from it
Hit = tuple[float, float, float]


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
    edge, (x3, y3, x43, y43, xmin, xmax, ymin, ymax) with the edge's own padded box; and per polygon the
    `Surface` the exact path tests (edges, centroid, span, from the world-frame vertices)."""

    def __init__(self, obstacles: Sequence[Sequence[Sequence[float]]]) -> None:
        self.polygons: list[PolygonBox] = []
        self.edges: list[list[Edge]] = []
        self.surfaces: list[Surface] = []
        for poly in obstacles:
            edges = polygon_edges(poly)
            self.edges.append(edges)
            self.surfaces.append((edges, centroid(poly), span(poly)))
            table: list[tuple[float, ...]] = []
            for x3, y3, x4, y4 in edges:
                table.append((x3, y3, x4 - x3, y4 - y3, min(x3, x4) - CULL_PAD, max(x3, x4) + CULL_PAD,
                              min(y3, y4) - CULL_PAD, max(y3, y4) + CULL_PAD))
            xs = [p[0] for p in edges]
            ys = [p[1] for p in edges]
            self.polygons.append((min(xs) - CULL_PAD, max(xs) + CULL_PAD, min(ys) - CULL_PAD,
                                  max(ys) + CULL_PAD, table))
        # the largest padded box's width plus height (culled_crossings' `size`)
        self.largest = max(((p[1] - p[0]) + (p[3] - p[2]) for p in self.polygons), default=0.0)

    def near(self, x: float, y: float, reach: float) -> list[PolygonBox]:
        """The obstacles whose padded box meets the square of half-side `reach` around (x, y): everything
        a body lying within `reach` of (x, y) could touch."""
        return boxes_near(self.polygons, x, y, reach)


def boxes_near(polygons: Sequence[PolygonBox], x: float, y: float, reach: float) -> list[PolygonBox]:
    """`ObstacleEdges.near` among `polygons`, in their order. Among the boxes near (x, y) for a longer
    reach it finds the same as among all: x + reach and the other bounds round monotonically in reach."""
    return [p for p in polygons
            if not (x + reach < p[0] or x - reach > p[1] or y + reach < p[2] or y - reach > p[3])]


# The fast loop's band, in units of the edge parameters: outside [-BAND, BAND] and [1 - BAND, 1 + BAND]
# it decides u_a and u_b from their values alone, when |d| is large enough for the margins to be smaller.
BAND = 2.0 ** -20
LOW = -BAND
HIGH = 1.0 + BAND
INNER = 1.0 - BAND
ROUNDOFF = 8 * U

# (slack, big, steady, floor, scale) of one placement: see `tolerance` and `culled_crossings`
Tolerance = tuple[float, float, float, float, float]


def tolerance(slack: float, size: float) -> Tolerance:
    """The fast loop's margins for vertices within `slack` of the original's in each coordinate, against
    obstacles such that `size` bounds the polygon's box width plus height plus any obstacle's. `floor` and
    `scale` bound a crossing point's error as floor + (|x21| + |y21|)*scale/|d| (see `culled_crossings`)."""
    size += 4 * slack
    big = size * (8 * slack + size * 2.0 ** -48)
    return slack, big, big * (1.0 + 4.0 / BAND), 6 * slack + size * ROUNDOFF, 3 * big


def _decide(d: float, na: float, nb: float, big: float) -> bool | None:
    """Whether edges with these d, n_a, n_b cross, the same for every evaluation within `big` of each of
    them; None when some evaluation might say otherwise."""
    big2 = 2 * big
    big3 = 3 * big
    if -big3 <= d <= big3:  # nearly parallel: u_a, u_b in [0, 1] needs |n_a|, |n_b| about as small as |d|
        if abs(na) > 6 * big or abs(nb) > 6 * big:
            return False
        return None
    if d < 0.0:  # signed so that u = n/d with d > 0
        d, na, nb = -d, -na, -nb
    for n in (na, nb):
        # surely below 0 or above 1 (fl(n/d) <= 1 up to n/d = 1 + 2**-53), else surely inside, else unknown
        if n < -big2 or n > d * (1 + 2.0 ** -52) + big3:
            return False
        if n <= big2 or n >= d - big3:
            return None
    return True


def culled_crossings(xs: Sequence[float], ys: Sequence[float], polygons: Sequence[PolygonBox],
                     margins: Tolerance | None = None,
                     box: tuple[float, float, float, float] | None = None) -> Iterator[Hit | None]:
    """The crossings of the closed polygon with world vertices (xs, ys) against `polygons`, with
    bounding-box culling that only skips pairs whose padded boxes are apart.

    Yields (px, py, error) for each crossing that the original's vertices (within `slack` of these in each
    coordinate; `margins` = tolerance(slack, size), default: these are the original's) give too, with the
    point taken along the polygon's edge as `crossing` does and `error` bounding how far the original's
    point lies from it; and None for each pair they might decide the other way. This is the hot loop of
    every step: it is written out flat for speed, and callers stop it at the first item when that is all
    they need.

    Why the margins hold: both evaluations are the same formula on inputs at most `slack` apart. With S
    bounding every |x21|, |y21|, |x43|, |y43|, |x13|, |y13| (the two boxes overlap, so their widths and
    heights summed do), each of d, n_a = x43*y13 - y43*x13 and n_b = x21*y13 - y21*x13 moves by at most
    about 6*S*slack through the inputs and 8*u*S**2 through the two evaluations' rounding; `big` =
    S*(8*slack + 2**-48*S) covers both (`tolerance`; its `size` is such an S for all of `polygons`).
    Where |d| >= `steady` = big*(1 + 4/BAND), u = n/d moves by at most (|u| + 1)*BAND/4 plus rounding, so
    u below -BAND or above 1 + BAND stays outside [0, 1] and u within [BAND, 1 - BAND] inside; everything
    else goes to `_decide`, which compares d, n_a and n_b with the margins themselves.

    `box` (xmin, xmax, ymin, ymax), when the caller knows one that holds every vertex (with `margins`),
    saves working out the vertices' own: it only culls obstacles and their edges, and every pair that
    goes on is tested on the polygon edge's own box, inside either, so the same pairs are tested.
    """
    if not polygons:
        return
    if box is None or margins is None:
        pxmin = min(xs)
        pxmax = max(xs)
        pymin = min(ys)
        pymax = max(ys)
    else:
        pxmin, pxmax, pymin, pymax = box
    n = len(xs)
    if margins is None:
        margins = tolerance(0.0, (pxmax - pxmin) + (pymax - pymin)
                            + max((p[1] - p[0]) + (p[3] - p[2]) for p in polygons))
    slack, big, steady, floor, scale = margins
    unsteady = -steady
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
                y13 = y1 - y3
                x13 = x1 - x3
                if unsteady < d < steady:
                    verdict = _decide(d, x43 * y13 - y43 * x13, x21 * y13 - y21 * x13, big)
                    ua = (x43 * y13 - y43 * x13) / d if verdict else 0.0  # |d| > 3*big when it crosses
                else:
                    ua = (x43 * y13 - y43 * x13) / d
                    if BAND < ua < INNER:
                        ub = (x21 * y13 - y21 * x13) / d
                        if BAND < ub < INNER:
                            verdict = True
                        elif ub < LOW or ub > HIGH:
                            continue
                        else:
                            verdict = _decide(d, x43 * y13 - y43 * x13, x21 * y13 - y21 * x13, big)
                    elif ua < LOW or ua > HIGH:
                        continue
                    else:
                        verdict = _decide(d, x43 * y13 - y43 * x13, x21 * y13 - y21 * x13, big)
                if not verdict:
                    if verdict is None:
                        yield None
                    continue
                # u_a moves by at most 2*big/(|d| - big) <= 3*big/|d| (|d| > 3*big) plus the divisions'
                # rounding (|n_a| <= |d|); the point by that times |x21| + |y21| (<= size), plus the
                # vertices' own slack and the rounding of x1 + x21*ua: `floor` (`tolerance`)
                error = floor + ((x21 if x21 > 0.0 else -x21) + (y21 if y21 > 0.0 else -y21)) * scale / (
                    d if d > 0.0 else -d)
                yield x1 + x21 * ua, y1 + y21 * ua, error
