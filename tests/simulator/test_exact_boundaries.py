"""Exact at the boundaries: where the last bits of a placement decide a collision or an IR reading, the
Simulator answers as the original does (tests/simulator/original_model.py), not as the plain transform
would. Cases from a differential check of 116k random and constructed placements (issue 20), and
constructed families of the same kinds."""

from __future__ import annotations

import random

import original_model as original

from simiam.physics.transform import transform_fast
from simiam.robot.quickbot import spec_for_week
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

