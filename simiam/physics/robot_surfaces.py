"""One robot's surfaces against the world, answered as the original's `Physics` answers them.

The base plate (`body_collision_detection`) and the IR cones (`proximity_sensor_detection`) are placed with
the plain transform and tested with the culled loop, which decides whatever the last bits of the vertices
cannot change. Where they might (a vertex within rounding of an edge, a raw value on a rounding boundary,
an edge nearly collinear with one the culling skipped), that one surface is placed with the original's
fused arithmetic (transform.transform_exact) and tested as the original does (precheck, every pair). Such
steps are rare (see docs/design.md, "Exact at the boundaries"), so the step costs what the fast path costs.

Other robots' plates (a Fleet) are tested as placed by the plain transform on both paths.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence

from simiam.physics.collision import plate_collides, plate_collides_exact
from simiam.physics.ir_ranging import cone_range, cone_range_exact
from simiam.physics.parallel import NONE, NearParallel
from simiam.physics.precheck import span
from simiam.physics.segments import (
    CULL_PAD,
    ObstacleEdges,
    PolygonBox,
    Surface,
    Tolerance,
    boxes_near,
    tolerance,
)
from simiam.physics.transform import fast_error, transform_exact, transform_fast
from simiam.robot.ir_sensor import distance_to_raw, mounted_cone, settled_raw
from simiam.robot.quickbot import RobotSpec

Pose = tuple[float, float, float]
Point = tuple[float, float]
Sensed = tuple[tuple[float, ...], tuple[int, ...]]  # the IR ranges (m) and raw values, one per sensor


def _capsule(cone: Sequence[Point]) -> tuple[float, float, float, float, float]:
    """(apex x, y, tip x, y, w) of a cone (robot frame, apex first, tip its fourth vertex, on the axis):
    every vertex lies within w of the segment from apex to tip, so in the world the cone's vertices lie
    within the box of the placed apex and tip widened by w in each coordinate. w has 1e-9 m to spare,
    far more than the rounding of any placement (about 1e-16 m)."""
    (ax, ay), (tx, ty) = cone[0], cone[3]
    dx, dy = tx - ax, ty - ay
    length2 = dx * dx + dy * dy
    w = 0.0
    for px, py in cone:
        u = ((px - ax) * dx + (py - ay) * dy) / length2 if length2 else 0.0
        u = min(max(u, 0.0), 1.0)
        w = max(w, math.hypot(px - ax - u * dx, py - ay - u * dy))
    return ax, ay, tx, ty, w + 1e-9


@functools.lru_cache(maxsize=16)
def _near_parallel(surfaces: tuple[tuple[Point, ...], ...], spans: tuple[float, ...],
                   obstacles: tuple[tuple[Point, ...], ...], reach: float) -> NearParallel:
    """One NearParallel per robot and world (it takes milliseconds to build, a Simulator microseconds)."""
    return NearParallel(surfaces, spans, ObstacleEdges(obstacles), reach)


class RobotSurfaces:
    """The base plate and IR cones of `spec` (robot frame) against `obstacles`."""

    def __init__(self, spec: RobotSpec, obstacles: Sequence[Sequence[Sequence[float]]]) -> None:
        self.spec = spec
        self.obstacles = ObstacleEdges(obstacles)
        self.plate = list(spec.base_plate)
        self.cones = [mounted_cone(m, spec.ir_max_range, spec.ir_spread) for m in spec.ir_mounts]
        self._cone_points = [p for cone in self.cones for p in cone]
        # the spans the original computes once, from the robot-frame geometry
        self._plate_span = span(self.plate)
        self._cone_spans = [span(cone) for cone in self.cones]
        # how far from the body origin the plate and the cones reach: obstacles farther away are skipped
        # for the whole step (ObstacleEdges.near is conservative, so nothing that could be hit is dropped)
        self._plate_reach = max(math.hypot(px, py) for px, py in self.plate)
        self._ir_reach = max(math.hypot(px, py) for px, py in self._cone_points)
        # culled_crossings' `size`: the robot's box (at most 2*reach a side) plus the largest obstacle's,
        # another robot's plate included (a Fleet)
        largest = max(self.obstacles.largest, 4 * self._plate_reach + 4 * CULL_PAD)
        self._plate_size = 4 * self._plate_reach + largest
        self._ir_size = 4 * self._ir_reach + largest
        # the fast loop's margins, worked out once for a robot anywhere within `_extent` of the origin in x
        # and y (margins for a farther robot hold for a nearer one too); beyond it, per pose
        self._extent = 4.0 + max((abs(c) for p in obstacles for v in p for c in v), default=0.0)
        self._plate_margins = self._margins(self._extent, self._plate_reach, self._plate_size)
        self._ir_margins = self._margins(self._extent, self._ir_reach, self._ir_size)
        # surface 0 is the plate, surface i + 1 the cone of sensor i
        surfaces = (tuple(self.plate), *self.cones)
        spans = (self._plate_span, *self._cone_spans)
        polygons = tuple(tuple((float(x), float(y)) for x, y in p) for p in obstacles)
        self._parallel = _near_parallel(surfaces, spans, polygons, max(self._plate_reach, self._ir_reach))
        self._quick = min(self._extent, self._parallel.far)  # where NearParallel.free holds
        self._raw_nothing = distance_to_raw(spec.ir_max_range, spec.ir_mode)
        self._open: Sensed = ((spec.ir_max_range,) * len(self.cones), (self._raw_nothing,) * len(self.cones))
        self._open_step = (False, *self._open)
        self._ranging = (spec.ir_min_range, spec.ir_max_range, spec.ir_mode)
        # (x, y, gap): from a body origin within gap of (x, y) in x and in y, the cones' reach meets no
        # obstacle's box (`step` skips the look-up there; `_clearance`); none known at first
        self._clear = (0.0, 0.0, -1.0)
        self._capsules = [_capsule(cone) for cone in self.cones]
        # the plate's nearby obstacles are those of the cones' reach that lie within its own (see `step`)
        self._plate_within_ir = self._plate_reach <= self._ir_reach

    def collides(self, pose: Pose, others: Sequence[ObstacleEdges] = ()) -> bool:
        """Whether the plate at `pose` touches an obstacle or one of `others` (other robots' plates)."""
        near = self.obstacles.near(pose[0], pose[1], self._plate_reach)
        if others:
            near += [o.polygons[0] for o in others]
        return self._collides(pose, near, 0 in self._flagged(pose), others)

    def sense(self, pose: Pose, others: Sequence[ObstacleEdges] = ()) -> Sensed:
        """The IR ranges (m) and raw values of every sensor with the robot at `pose`."""
        near = self.obstacles.near(pose[0], pose[1], self._ir_reach)
        if others:
            near += [o.polygons[0] for o in others]
        return self._sense(pose, near, self._flagged(pose), others)

    def step(self, pose: Pose) -> tuple[bool, tuple[float, ...], tuple[int, ...]]:
        """A lone robot's physics pass at `pose`: (True, (), ()) when the plate touches an obstacle,
        else (False, ranges, raws) as `sense` gives them. The same answers as `collides` then `sense`,
        which look up the nearby obstacles and the near-parallel surfaces once each; this looks them up
        once for both (the plate's obstacles are among the cones', whose reach is longer)."""
        x, y, theta = pose
        cx, cy, gap = self._clear
        if -gap <= x - cx <= gap and -gap <= y - cy <= gap:  # still in the clear square: nothing near
            near = []
        else:
            near = boxes_near(self.obstacles.polygons, x, y, self._ir_reach)
            if not near:
                self._clear = (x, y, self._clearance(x, y))
        lo, hi = self._parallel.free
        quick = self._quick
        if lo < theta < hi and -quick < x < quick and -quick < y < quick:  # `_flagged`'s shortcut, inline
            parallel = NONE
        else:
            parallel = self._parallel.flagged(x, y, theta)
        if not near and not parallel:  # open space (most steps): no collision, every cone reads max_range
            return self._open_step
        if self._plate_within_ir:
            plate_near = boxes_near(near, x, y, self._plate_reach)
        else:
            plate_near = self.obstacles.near(x, y, self._plate_reach)
        if self._collides(pose, plate_near, 0 in parallel, ()):
            return True, (), ()  # no IR pass after a collision (the original's apply_physics returns)
        ranges, raws = self._sense(pose, near, parallel, ())
        return False, ranges, raws

    def _clearance(self, x: float, y: float) -> float:
        """How far (in x and in y) the body origin may move from (x, y), where no obstacle is near for the
        cones' reach, with none coming near: each box stays apart, on the side where it is now, by its
        margin there, less 1e-9 m, far more than the rounding of x + reach and of these differences."""
        r = self._ir_reach
        return min((max(p[0] - (x + r), (x - r) - p[1], p[2] - (y + r), (y - r) - p[3])
                    for p in self.obstacles.polygons), default=math.inf) - 1e-9

    def _collides(self, pose: Pose, near: list[PolygonBox], parallel: bool,
                  others: Sequence[ObstacleEdges]) -> bool:
        """`collides` with the nearby obstacles (others' plates included) and the flag looked up."""
        if near:
            x, y, _ = pose
            xs, ys = transform_fast(pose, self.plate)
            margins = self._plate_margins
            if not (-self._extent < x < self._extent and -self._extent < y < self._extent):
                margins = self._margins(max(abs(x), abs(y)), self._plate_reach, self._plate_size)
            verdict = plate_collides(xs, ys, near, margins)
            if verdict:  # a crossing every nearby placement has: the original finds it too
                return True
            if verdict is False and not parallel:
                return False
        elif not parallel:
            return False
        xs, ys = transform_exact(pose, self.plate)
        return plate_collides_exact(list(zip(xs, ys, strict=True)), self._surfaces(others), self._plate_span)

    def _sense(self, pose: Pose, near: list[PolygonBox], parallel: frozenset[int],
               others: Sequence[ObstacleEdges]) -> Sensed:
        """`sense` with the nearby obstacles (others' plates included) and the flagged surfaces looked up.

        A cone is placed only when its capsule (`_capsule`) meets a nearby obstacle's padded box: every
        other cone's vertices lie apart from every such box, where culled_crossings finds nothing and the
        range is max_range. A placed cone's vertices are transform_fast's, computed the same way."""
        if not near and not parallel:  # open space: every cone reads max_range
            return self._open
        lo, hi, mode = self._ranging
        ranges = list(self._open[0])
        raws = list(self._open[1])
        x, y, theta = pose
        c, s = math.cos(theta), math.sin(theta)  # as transform_fast computes them
        margins = None
        for i, (ax, ay, tx, ty, w) in enumerate(self._capsules):
            if parallel and i + 1 in parallel:
                d = self._cone_exact(pose, i, others)
            elif near:
                x0 = c * ax - s * ay + x
                x1 = c * tx - s * ty + x
                y0 = s * ax + c * ay + y
                y1 = s * tx + c * ty + y
                if x0 > x1:
                    x0, x1 = x1, x0
                if y0 > y1:
                    y0, y1 = y1, y0
                x0 -= w
                x1 += w
                y0 -= w
                y1 += w
                for p in near:
                    if not (x1 < p[0] or x0 > p[1] or y1 < p[2] or y0 > p[3]):
                        break
                else:  # apart from every nearby box: nothing crosses this cone
                    continue
                cone = self.cones[i]
                xs = [c * px - s * py + x for px, py in cone]
                ys = [s * px + c * py + y for px, py in cone]
                if margins is None:
                    margins = self._ir_margins
                    if not (-self._extent < x < self._extent and -self._extent < y < self._extent):
                        margins = self._margins(max(abs(x), abs(y)), self._ir_reach, self._ir_size)
                found = cone_range(xs, ys, near, lo, hi, margins, (x0, x1, y0, y1))  # the capsule's box
                if found is None:
                    d = self._cone_exact(pose, i, others)
                elif found[0] == hi and not found[1]:  # nothing crossed this cone
                    continue
                else:
                    raw = settled_raw(found[0], found[1], mode)
                    if raw is not None:
                        ranges[i] = found[0]
                        raws[i] = raw
                        continue
                    d = self._cone_exact(pose, i, others)
            else:
                continue
            ranges[i] = d
            raws[i] = distance_to_raw(d, mode)
        return tuple(ranges), tuple(raws)

    @staticmethod
    def _margins(extent: float, reach: float, size: float) -> Tolerance:
        """segments.tolerance for a surface within `reach` of a body origin within `extent` of the world's
        in x and y, against obstacles such that `size` bounds the boxes (see __init__)."""
        return tolerance(fast_error(reach, extent + reach), size)

    def _flagged(self, pose: Pose) -> frozenset[int]:
        """NearParallel.flagged (surface 0 the plate, i + 1 cone i); most steps only test its free stretch."""
        x, y, theta = pose
        lo, hi = self._parallel.free
        quick = self._quick
        if lo < theta < hi and -quick < x < quick and -quick < y < quick:
            return NONE
        return self._parallel.flagged(x, y, theta)

    def plate_at(self, pose: Pose) -> ObstacleEdges:
        """The base plate at `pose` as an obstacle for other robots (a Fleet), plainly transformed."""
        xs, ys = transform_fast(pose, self.plate)
        return ObstacleEdges([list(zip(xs, ys, strict=True))])

    def _cone_exact(self, pose: Pose, i: int, others: Sequence[ObstacleEdges]) -> float:
        """Cone i's range as the original computes it, on the original's vertices."""
        spec = self.spec
        xs, ys = transform_exact(pose, self.cones[i])
        return cone_range_exact(list(zip(xs, ys, strict=True)), self._surfaces(others), spec.ir_min_range,
                                spec.ir_max_range, self._cone_spans[i])

    def _surfaces(self, others: Sequence[ObstacleEdges]) -> list[Surface]:
        return self.obstacles.surfaces + [o.surfaces[0] for o in others]
