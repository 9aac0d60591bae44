"""The original's broad phase (`Surface2D.precheck_surface`), in its arithmetic.

Before testing two surfaces edge against edge, the original compares the distance between their centroids
(the mean of the vertices) with (span_a + span_b)/sqrt(3), where a span is twice the largest distance of a
vertex from the centroid, computed once when the surface is built. For two surfaces that really touch the
centroids are at most (span_a + span_b)/2 apart, so the test never drops a real crossing; what it does drop
are the crossings the edge formula reports between far-apart edges that are nearly collinear (rounding, not
geometry). The exact path (collision.plate_collides_exact, ir_ranging.cone_range_exact) applies it so that it
reports those exactly when the original does, and simiam.physics.parallel relies on it to bound how far
apart such edges can be.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

Point = tuple[float, float]


def centroid(points: Sequence[Sequence[float]]) -> Point:
    """sum(geometry(:, 1:2), 1)/n: each coordinate summed in vertex order, then divided by n."""
    sx = 0.0
    sy = 0.0
    for p in points:
        sx += p[0]
        sy += p[1]
    n = len(points)
    return sx / n, sy / n


def span(points: Sequence[Sequence[float]]) -> float:
    """2*max(sqrt((x - cx).^2 + (y - cy).^2)) over the vertices, around their centroid."""
    cx, cy = centroid(points)
    return 2 * max(math.sqrt((p[0] - cx) ** 2 + (p[1] - cy) ** 2) for p in points)


def precheck(a: Point, span_a: float, b: Point, span_b: float) -> bool:
    """Whether the original goes on to test the edges of surfaces with centroids a, b and these spans."""
    d = math.sqrt((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2)
    return d < (span_a + span_b) / math.sqrt(3)
