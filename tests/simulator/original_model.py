"""The original's Physics for one QuickBot, written out from `Surface2D.m` and `Physics.m` (sp14) for the
tests to compare the Simulator with: slow, plain, and independent of simiam.physics.

- Surfaces are placed by `vertex_set * T'`, whose BLAS evaluated each coordinate with one fused
  multiply-add: x_w = fl(fma(y, -sin, fl(x*cos)) + t_x); here the fma is exact rational arithmetic rounded
  once. The sensor cone is placed twice that way: by its mount, then by the pose.
- `precheck_surface`: centroid distance < (span_a + span_b)/sqrt(3); centroids are vertex means, spans twice
  the largest vertex distance from the centroid of the geometry the surface was built with.
- `intersection_with_surface`: every edge pair, u_a and u_b by the formula in floating point, both in
  [0, 1]; the point along edge a.
- collision: any point; IR: the nearest point from the apex, each clamped to [0.04, 0.3].
"""

from __future__ import annotations

import math
from fractions import Fraction

from simiam.robot.ir_sensor import cone_polygon, distance_to_raw
from simiam.robot.quickbot import RobotSpec

LO, HI = 0.04, 0.3


def place(pose, points):
    x, y, theta = pose
    c, s = math.cos(theta), math.sin(theta)
    return [(float(Fraction(py) * Fraction(-s) + Fraction(px * c)) + x,
             float(Fraction(py) * Fraction(c) + Fraction(px * s)) + y) for px, py in points]


def centroid(points):
    sx = sy = 0.0
    for px, py in points:
        sx += px
        sy += py
    return sx / len(points), sy / len(points)


def span(points):
    cx, cy = centroid(points)
    return 2 * max(math.sqrt((px - cx) ** 2 + (py - cy) ** 2) for px, py in points)


def edges(points):
    n = len(points)
    return [(*points[k], *points[(k + 1) % n]) for k in range(n)]


def points_between(a_points, b_points):
    """`intersection_with_surface`: the crossing points of every edge pair, taken along a's edges."""
    out = []
    for x1, y1, x2, y2 in edges(a_points):
        for x3, y3, x4, y4 in edges(b_points):
            y13, x13, x21, y21, x43, y43 = y1 - y3, x1 - x3, x2 - x1, y2 - y1, x4 - x3, y4 - y3
            d = y43 * x21 - x43 * y21
            if d == 0.0:  # MATLAB divides and gets Inf or NaN, which no comparison keeps
                continue
            ua = (x43 * y13 - y43 * x13) / d
            ub = (x21 * y13 - y21 * x13) / d
            if 0.0 <= ua <= 1.0 and 0.0 <= ub <= 1.0:
                out.append((x1 + x21 * ua, y1 + y21 * ua))
    return out


def precheck(a_world, a_span, b_world):
    (ax, ay), (bx, by) = centroid(a_world), centroid(b_world)
    return math.sqrt((ax - bx) ** 2 + (ay - by) ** 2) < (a_span + span(b_world)) / math.sqrt(3)


def collides(spec: RobotSpec, pose, obstacles) -> bool:
    plate = place(pose, spec.base_plate)
    return any(precheck(plate, span(spec.base_plate), ob) and points_between(plate, ob) for ob in obstacles)


def ir_raws(spec: RobotSpec, pose, obstacles) -> list[int]:
    raws = []
    for mount in spec.ir_mounts:
        robot_frame = place(mount, cone_polygon(spec.ir_max_range, spec.ir_spread))
        cone = place(pose, robot_frame)
        (ax, ay), d_min = cone[0], HI
        for ob in obstacles:
            if precheck(cone, span(robot_frame), ob):
                for px, py in points_between(cone, ob):
                    d_min = min(d_min, min(max(math.sqrt((px - ax) ** 2 + (py - ay) ** 2), LO), HI))
        raws.append(distance_to_raw(d_min, spec.ir_mode))
    return raws
