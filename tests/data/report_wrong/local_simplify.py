"""A wrong line simplification for the compact plots (tests/report/test_compact_plots.py): each point is
dropped when it lies near the line from the last point kept to the next one, so a gentle arc drifts away
point by point and collapses into one straight segment far from most of the arc."""

from __future__ import annotations


def simplified(points: list[tuple[float, float]], tolerance: float = 0.5) -> list[tuple[float, float]]:
    if len(points) < 3:
        return points
    kept = [points[0]]
    for k in range(1, len(points) - 1):
        (ax, ay), (bx, by), (x, y) = kept[-1], points[k + 1], points[k]
        dx, dy = bx - ax, by - ay
        length = dx * dx + dy * dy
        if length == 0 or ((x - ax) * dy - (y - ay) * dx) ** 2 > tolerance * tolerance * length:
            kept.append(points[k])
    kept.append(points[-1])
    return kept
