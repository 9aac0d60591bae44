"""The IR cone model: edge crossings only, distances from the apex, clamped to [0.04, 0.3]."""

from __future__ import annotations

import math

import numpy as np
import pytest
from sim_helpers import wrong

from simiam.physics.ir_ranging import cone_range, cone_range_exact
from simiam.physics.segments import ObstacleEdges
from simiam.robot.ir_sensor import cone_polygon

SPREAD = 6 * math.pi / 180
CONE = cone_polygon(0.3, SPREAD)


def box(x0, y0, x1, y1):
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)


def centre_ray(xs, ys, polygons, lo, hi):
    """WRONG: the sensor axis only (a 2-vertex 'cone')."""
    return cone_range([xs[0], xs[3]], [ys[0], ys[3]], polygons, lo, hi)[0]


# (name, obstacles in the sensor frame, expected range)
CASES = [
    # a wall across the axis at 5 cm is first crossed by the outer cone edges, at 0.05 / cos(3.0041 deg)
    ("perpendicular wall", [box(0.05, -1, 0.2, 1)], 0.05 / math.cos(math.asin(math.tan(SPREAD / 2)))),
    ("nearer than 4 cm", [box(0.01, -1, 0.2, 1)], 0.04),
    ("nothing in range", [box(0.35, -1, 0.5, 1)], 0.3),
    ("wholly inside the cone: not seen", [box(0.1, -0.001, 0.12, 0.001)], 0.3),
    ("beside the axis, inside the cone's side edge", [box(0.1, 0.004, 0.2, 0.5)], None),
]


@pytest.mark.parametrize("ranger", [cone_range, "exact"], ids=["fast", "exact"])
def test_cone_cases(ranger):
    xs, ys = [p[0] for p in CONE], [p[1] for p in CONE]
    for name, obstacles, want in CASES:
        edges = ObstacleEdges(obstacles)
        if ranger == "exact":
            got = cone_range_exact(CONE, edges.surfaces, 0.04, 0.3)
        else:
            got, _ = ranger(xs, ys, edges.polygons, 0.04, 0.3)  # none of these is undecided
        if want is None:  # seen by the cone's side edge, where the axis sees nothing
            assert 0.04 < got < 0.2, name
        else:
            assert got == pytest.approx(want, abs=1e-15), name


def test_centre_ray_is_caught():
    xs, ys = [p[0] for p in CONE], [p[1] for p in CONE]
    wrong = []
    for name, obstacles, want in CASES:
        got = centre_ray(xs, ys, ObstacleEdges(obstacles).polygons, 0.04, 0.3)
        if (want is None and not 0.04 < got < 0.2) or (want is not None and abs(got - want) > 1e-15):
            wrong.append(name)
    assert "perpendicular wall" in wrong and "beside the axis, inside the cone's side edge" in wrong


def cone_problems(cone_fn) -> list:
    """reference/original-simulator.md 2.1: apex first, then five far points on the circle of radius r at
    angles +asin(tan 3 deg), +asin(tan 1.5 deg), 0, -asin(tan 1.5 deg), -asin(tan 3 deg)."""
    r = 0.3
    cone = cone_fn(r, SPREAD)
    out = [] if cone[0] == (0.0, 0.0) and len(cone) == 6 else ["apex / vertex count"]
    for (px, py), half in zip(cone[1:], (SPREAD / 2, SPREAD / 4, 0.0, -SPREAD / 4, -SPREAD / 2), strict=True):
        angle = math.asin(math.tan(half))
        if abs(px - r * math.cos(angle)) > 1e-15 or abs(py - r * math.tan(half)) > 1e-15:
            out.append((px, py, half))
    return out


def test_cone_vertices_as_the_original():
    assert cone_problems(cone_polygon) == []


def test_cone_vertex_check_catches_arc_angles():
    assert cone_problems(wrong("ir_wrong").cone_polygon_arc_angles)
