"""Near-parallel edges: the culled pairs the original's crossing formula may still report.

The fast loop (segments.culled_crossings) skips an obstacle edge whose padded box is apart from a robot
edge's, so the two are at least g = CULL_PAD (less the slack of the fast transform) apart and cannot cross.
The original tests every pair of surfaces that pass its precheck, and its formula, in rounding, reports a
crossing for two such edges when they are nearly collinear: d, n_a and n_b are then all rounding noise.

How parallel must they be? With u = 2**-53, the formula computes d = y43*x21 - x43*y21 within
4.01*u*|a|*|b| of its exact value and n_a, n_b within 4.01*u*|b|*|p13| and 4.01*u*|a|*|p13| (|p13| the
distance between the edges' first vertices). If it reports, the exact line parameters lie within
u + (1.01*E_d + E_n)/|D| of [0, 1]; since the segments are g apart, one of them lies at least g/(2|a|)
(or g/(2|b|)) outside. Together: |sin(angle)| = |D|/(|a||b|) <= 8.02*u*(1.01*L + |p13|)/(g - 2*u*L),
with L = max(|a|, |b|). The precheck bounds |p13| by the two spans: at most
(0.5 + 1/sqrt(3))*(span_a + span_b) < 1.08*(span_a + span_b).

So for each robot edge (in the robot frame, direction phi) and obstacle edge (direction psi), the heading
theta at which the pair is within that angle of parallel lies in a narrow interval around psi - phi
(mod pi). `NearParallel` merges those intervals once per world; a step asks which robot surfaces have such
a pair at its heading (one bisection), and only those take the exact path. With the week-4 world about one
step in 400 does.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence

from simiam.physics.segments import CULL_PAD, Edge, ObstacleEdges, U, polygon_edges

Point = tuple[float, float]

# Room in each interval for what the bound above does not count: the reduction of theta mod pi, the
# directions' atan2 and the vertices' rounding in the world. `flagged` checks that room is enough.
ROOM = 1e-9
NONE: frozenset[int] = frozenset()


def _vectors(edges: Sequence[Edge]) -> list[tuple[float, float]]:
    """Each edge (x1, y1, x2, y2) as its vector (x2 - x1, y2 - y1)."""
    return [(e[2] - e[0], e[3] - e[1]) for e in edges]


class NearParallel:
    """Which robot surfaces (the base plate, the IR cones: `surfaces`, robot frame, with the spans the
    original computed for them) have an edge nearly parallel to an obstacle edge at a heading theta."""

    def __init__(self, surfaces: Sequence[Sequence[Point]], spans: Sequence[float], obstacles: ObstacleEdges,
                 reach: float) -> None:
        self.count = len(surfaces)
        self.reach = reach
        gap = CULL_PAD / 2  # the culled pairs' distance, less the fast transform's slack with room to spare
        intervals: list[tuple[float, float, int]] = []
        self.shortest = math.inf
        for index, (surface, surface_span) in enumerate(zip(surfaces, spans, strict=True)):
            for ax, ay in _vectors(polygon_edges(surface)):
                length_a = math.hypot(ax, ay)
                self.shortest = min(self.shortest, length_a)
                phi = math.atan2(ay, ax)
                for edges, _, obstacle_span in obstacles.surfaces:
                    near = 1.08 * (surface_span + obstacle_span) + 1e-9
                    for bx, by in _vectors(edges):
                        length = max(length_a, math.hypot(bx, by))
                        room = gap - 2 * U * length  # <= 0 only for edges of millions of metres
                        sine = 8.02 * 1.01 * U * (length + near) / room if room > 0 else math.inf
                        # the angle from its sine, with room for asin's growth and for ROOM itself
                        half = math.pi if sine > 0.1 else 1.01 * sine + 2 * ROOM
                        centre = math.fmod(math.atan2(by, bx) - phi, math.pi)
                        for c in (centre - math.pi, centre, centre + math.pi):
                            if c + half >= 0.0 and c - half <= math.pi:
                                intervals.append((c - half, c + half, index))
        self._starts: list[float] = [-math.inf]  # a sentinel before the first interval
        self._ends: list[float] = [-math.inf]
        self._which: list[frozenset[int]] = [NONE]
        for lo, hi, index in sorted(intervals):
            if lo <= self._ends[-1]:
                self._ends[-1] = max(self._ends[-1], hi)
                self._which[-1] = self._which[-1] | {index}
            else:
                self._starts.append(lo)
                self._ends.append(hi)
                self._which.append(frozenset((index,)))

        # theta mod pi is exact, but pi is not: the reduction is off by |theta|/pi * 1.3e-16; the world
        # vertices' rounding turns an edge by at most 2*sqrt(2)*slack/|a|. Half of ROOM for each: the
        # intervals hold while |theta| < self._turns and |x|, |y| < self._far
        self._turns = ROOM / 2 / 2.0 ** -50
        self.far = ((ROOM / 2) * self.shortest / (3 * 2.0 ** -51) - 4 * reach) / 2
        # a stretch of headings known to flag nothing for |x|, |y| < far (the last one found): a caller
        # may test it itself before calling `flagged`, which it saves most steps
        self.free = (0.0, 0.0)

    def flagged(self, x: float, y: float, theta: float) -> frozenset[int]:
        """The surfaces (indices into `surfaces`) with an edge nearly parallel to an obstacle edge when the
        robot is at (x, y, theta): for those the fast path's culling may drop what the original reports."""
        far = self.far
        if not (-far < x < far and -far < y < far and -self._turns < theta < self._turns):
            return frozenset(range(self.count))  # no interval is known to be wide enough out there
        lo, hi = self.free
        if lo < theta < hi:  # most steps: still between the same two intervals as last time
            return NONE
        t = math.fmod(theta, math.pi)
        if t < 0.0:
            t += math.pi
        i = bisect.bisect_right(self._starts, t) - 1
        if t <= self._ends[i]:
            return self._which[i]
        # remember the free stretch around theta, between the intervals either side (wrapped round by pi
        # past the last or before the first; everything when there are none)
        last = len(self._starts) - 1
        before = self._ends[i] if i else (self._ends[last] - math.pi if last else -math.inf)
        after = self._starts[i + 1] if i < last else (self._starts[1] + math.pi if last else math.inf)
        self.free = (max(theta - (t - before), -self._turns), min(theta + (after - t), self._turns))
        return NONE
