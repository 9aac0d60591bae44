"""Exact at the boundaries: where the last bits of a placement decide a collision or an IR reading, the
Simulator answers as the original does (tests/simulator/original_model.py), not as the plain transform and
the culling would. Cases from a differential check of 116k random and constructed placements (issue 20),
and constructed families of the same kinds."""

from __future__ import annotations

import random

import original_model as original

from simiam.course.weeks import spec_for_week
from simiam.physics.transform import transform_fast
from simiam.simulator import ConstantBrain, Simulator
from simiam.world import load_world
from simiam.world.world import World

SPEC = spec_for_week(4)


def at(world: World, pose) -> Simulator:
    return Simulator(world, ConstantBrain(0.0, 0.0), SPEC, start=pose)


def test_collision_decided_by_the_fused_transform():
    """A plate edge passes within 1e-17 of the corner of the top wall at (-1.6, 1.6): with the original's
    fused placement it misses both of the corner's edges, with the plain one it crosses them."""
    world = load_world("week4")
    pose = (-1.5273881981186255, 1.6899644768995725, 31.95379351715816)
    assert original.collides(SPEC, pose, world.obstacles) is False
    xs, ys = transform_fast(pose, SPEC.base_plate)
    plain = [tuple(p) for p in zip(xs, ys, strict=True)]
    assert any(original.points_between(plain, ob) for ob in world.obstacles)  # the plain placement hits
    assert at(world, pose).touches_obstacle() is False


# One triangle whose first edge lies on the line of sensor 4's cone edge (apex to its left far point),
# beyond the far point: the boxes are apart, yet the original's formula, in rounding, reports a crossing
# 0.0 m from the apex (raw 917).
TRIANGLE = [(0.9948132515069633, 0.5821961220321773), (1.0756517399712862, 0.8436661640717248),
            (0.8919252661637024, 0.7572373271735517)]
TRIANGLE_POSE = (0.8201089442356515, 0.012332271373838744, 2.0039151423240735)


def test_ir_reports_the_collinear_edge_the_culling_kept_apart():
    world = World("one triangle", [TRIANGLE])
    assert original.ir_raws(SPEC, TRIANGLE_POSE, world.obstacles) == [133, 133, 133, 917, 133]
    assert at(world, TRIANGLE_POSE).ir_raw == (133, 133, 133, 917, 133)


def collinear_triangle(rng: random.Random, pose, sensor: int) -> list[tuple[float, float]]:
    """A triangle with one edge on the line of one of the sensor's two cone side edges, behind the apex or
    beyond the far point (rounded to doubles, so collinear up to rounding), its third vertex off to the
    side away from the cone."""
    cone = original.place(pose, original.place(SPEC.ir_mounts[sensor],
                                                 original.cone_polygon(0.3, SPEC.ir_spread)))
    (ax, ay), (fx, fy), (cx, cy) = cone[0], cone[rng.choice([1, 5])], cone[3]
    t3 = rng.choice([rng.uniform(1.0, 2.0), rng.uniform(-1.5, 0.0)])
    t4 = t3 + rng.uniform(0.05, 1.0) * (1 if t3 > 0 else -1)
    p3 = (ax + t3 * (fx - ax), ay + t3 * (fy - ay))
    p4 = (ax + t4 * (fx - ax), ay + t4 * (fy - ay))
    nx, ny = ay - fy, fx - ax
    side = 0.5 if nx * (cx - ax) + ny * (cy - ay) < 0 else -0.5
    return [p3, p4, ((p3[0] + p4[0]) / 2 + side * nx, (p3[1] + p4[1]) / 2 + side * ny)]


def test_constructed_collinear_edges_read_as_the_original():
    """About one such triangle in fifty is reported by the original's formula (or by the plain placement's)
    and decides a reading: all of them must read as the original."""
    rng = random.Random(2004)
    wrong, seen = [], 0
    for _ in range(400):
        pose = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-7, 7))
        world = World("collinear", [collinear_triangle(rng, pose, rng.randrange(5))])
        want = original.ir_raws(SPEC, pose, world.obstacles)
        seen += want != [133] * 5
        got = list(at(world, pose).ir_raw)
        if got != want:
            wrong.append((pose, world.obstacles[0], got, want))
    assert seen >= 4  # the family does reach the cases
    assert wrong == []


def corner_on_plate_edge(rng: random.Random, pose) -> list[tuple[float, float]]:
    """A triangle with a corner on one of the plate's edges as placed (rounded to doubles, so on it up to
    rounding), pointing into the plate or away from it."""
    plate = original.place(pose, SPEC.base_plate)
    k = rng.randrange(len(plate))
    (x1, y1), (x2, y2) = plate[k], plate[(k + 1) % len(plate)]
    t = rng.choice([0.0, 1.0, rng.random()])
    corner = (x1 + t * (x2 - x1), y1 + t * (y2 - y1))
    nx, ny = (y2 - y1, x1 - x2) if rng.random() < 0.5 else (y1 - y2, x2 - x1)
    return [corner, (corner[0] + 3 * nx - (x2 - x1), corner[1] + 3 * ny - (y2 - y1)),
            (corner[0] + 3 * nx + (x2 - x1), corner[1] + 3 * ny + (y2 - y1))]


def test_constructed_corner_contacts_collide_as_the_original():
    """An obstacle corner on a plate edge: touching counts, so the last bits of the placement decide."""
    rng = random.Random(2005)
    wrong, hits = [], 0
    for _ in range(400):
        pose = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-7, 7))
        world = World("corner", [corner_on_plate_edge(rng, pose)])
        want = original.collides(SPEC, pose, world.obstacles)
        hits += want
        if at(world, pose).touches_obstacle() != want:
            wrong.append((pose, world.obstacles[0], want))
    assert 0 < hits < 400
    assert wrong == []


def test_the_precheck_drops_a_far_collinear_edge_as_the_original():
    """Far along the line of sensor 2's cone edge, the formula (in rounding) reports a crossing 0.0 m from
    the apex, but the original never tests that triangle: its centroid is too far from the cone's."""
    from simiam.physics.ir_ranging import cone_range_exact
    from simiam.physics.segments import ObstacleEdges
    from simiam.physics.transform import transform_exact

    pose = (0.8776749967484598, 0.75594738261318, -2.6506424362512)
    triangle = [(0.3746213201685409, -1.1599328420806632), (0.34174607227659304, -1.2931093827372835),
                (0.5038122098666802, -1.2624701876934132)]
    world = World("far triangle", [triangle])
    assert original.ir_raws(SPEC, pose, world.obstacles) == [133] * 5
    assert at(world, pose).ir_raw == (133,) * 5
    xs, ys = transform_exact(pose, at(world, pose)._surfaces.cones[1])
    cone = list(zip(xs, ys, strict=True))
    surfaces = ObstacleEdges([triangle]).surfaces
    assert cone_range_exact(cone, surfaces, 0.04, 0.3, cone_span=100.0) == 0.04  # no precheck: reported
