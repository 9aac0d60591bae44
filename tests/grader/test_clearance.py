"""The pure-Python plate-obstacle gap (grader/clearance.py) agrees with shapely's Polygon.distance, which it
replaced to keep shapely and numpy out of the grading process."""

from __future__ import annotations

import math
import random

import pytest
from shapely.geometry import MultiPolygon, Polygon

from grader import clearance
from grader.scenarios import min_clearance
from simiam.course.weeks import get_week
from simiam.trace import Trace
from simiam.world import load_world

SPEC = get_week(4).spec
PLATE = SPEC.base_plate


def _plate_at(x: float, y: float, th: float) -> list[tuple[float, float]]:
    c, s = math.cos(th), math.sin(th)
    return [(x + c * px - s * py, y + s * px + c * py) for px, py in PLATE]


@pytest.mark.parametrize("world", ["week3", "week4", "final"])
def test_the_gap_is_shapelys_for_plates_all_over_the_world(world: str) -> None:
    obstacles = load_world(world).obstacles
    theirs_all = MultiPolygon([Polygon(p) for p in obstacles])
    shapes = [clearance.Shape(p) for p in obstacles]
    rng = random.Random(world)
    touching = 0
    for _ in range(400):
        body = _plate_at(rng.uniform(-1.6, 1.6), rng.uniform(-1.6, 1.6), rng.uniform(-math.pi, math.pi))
        ours = min(clearance.distance(clearance.Shape(body), s) for s in shapes)
        theirs = Polygon(body).distance(theirs_all)
        assert ours == pytest.approx(theirs, rel=1e-12, abs=1e-15), body
        touching += theirs == 0.0
    assert 0 < touching < 400  # both overlapping and clear plates were tried


def test_a_plate_inside_an_obstacle_or_around_one_has_no_gap() -> None:
    big = clearance.Shape([(-1, -1), (1, -1), (1, 1), (-1, 1)])
    small = clearance.Shape([(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)])
    assert clearance.distance(small, big) == 0.0 and clearance.distance(big, small) == 0.0
    apart = clearance.Shape([(2, 0), (3, 0), (3, 1)])
    assert clearance.distance(big, apart) == 1.0


def test_min_clearance_of_a_run_is_shapelys() -> None:
    world = load_world("week4")
    spec = SPEC
    xs = [i * 0.01 - 0.5 for i in range(120)]
    trace = Trace(week=4, dt=0.05, world={}, robot={}, start=[0, 0, 0],
                  steps={"x": xs, "y": [0.1 * math.sin(x * 5) for x in xs],
                         "theta": [x * 2 for x in xs]})
    ours = min_clearance(trace, world, spec)
    theirs_all = MultiPolygon([Polygon(p) for p in world.obstacles])
    rows = range(120)  # every step: a margin read from every third overstated this run's by 0.04 mm
    theirs = min(Polygon(_plate_at(trace.steps["x"][k], trace.steps["y"][k], trace.steps["theta"][k]))
                 .distance(theirs_all) for k in rows)
    assert ours == pytest.approx(theirs, rel=1e-12, abs=1e-15)


def _every_pair(a: clearance.Shape, b: clearance.Shape) -> float:
    """The distance with nothing skipped: every edge pair crossed, every vertex against every edge."""
    if any(clearance._crosses(e, f) for e in a.edges for f in b.edges):
        return 0.0
    if clearance._inside(a.points[0], b) or clearance._inside(b.points[0], a):
        return 0.0
    return min([clearance.point_to_segment(p, r, s) for p in a.points for r, s in b.edges]
               + [clearance.point_to_segment(p, r, s) for p in b.points for r, s in a.edges])


@pytest.mark.parametrize("world", ["week3", "week4", "final"])
def test_skipping_pairs_never_changes_the_gap_by_a_bit(world: str) -> None:
    """nearer() skips box-separated polygons' crossing tests and vertex-edge pairs whose box gap exceeds
    the best so far: the result is min(bound, the full computation) exactly, for plates close to the
    obstacles (where the skipping decides) and bounds just above, at and below the true gap."""
    shapes = [clearance.Shape(p) for p in load_world(world).obstacles]
    rng = random.Random(f"nearer-{world}")
    skipped_some = 0
    for _ in range(300):
        obstacle = rng.choice(shapes)
        x0, x1, y0, y1 = obstacle.box
        body = clearance.Shape(_plate_at(rng.uniform(x0 - 0.15, x1 + 0.15), rng.uniform(y0 - 0.15, y1 + 0.15),
                                         rng.uniform(-math.pi, math.pi)))
        exact = _every_pair(body, obstacle)
        assert clearance.distance(body, obstacle) == exact
        for bound in (math.inf, exact, math.nextafter(exact, math.inf), exact * 1.01 + 1e-6,
                      exact * 0.99, rng.uniform(0, 0.5)):
            assert clearance.nearer(body, obstacle, bound) == min(bound, exact), (bound, exact)
        skipped_some += exact > 0 and clearance.box_gap(body.box, obstacle.box) > 0
    assert skipped_some > 10  # plates clear of the obstacle's box, whose crossing tests are skipped
