"""Body collisions: edge crossings with closed intervals (touching counts); containment is not detected."""

from __future__ import annotations

import numpy as np
import pytest
from sim_helpers import wrong

from simiam.physics.collision import plate_collides, plate_collides_exact
from simiam.physics.segments import ObstacleEdges, tolerance
from simiam.physics.transform import transform_fast
from simiam.robot.quickbot import BASE_PLATE

FRONT = 0.0686  # the base plate's front vertex (0.0686, 0)
SIDE = 0.0534  # the plate's left edge (-0.0465, 0.0534)-(0.0335, 0.0534)


def box(x0, y0, x1, y1):
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)


# (name, pose, obstacles, expected)
CASES = [
    ("touching the front vertex", (0.0, 0.0, 0.0), [box(FRONT, -0.5, 1.0, 0.5)], True),
    ("crossing", (0.0, 0.0, 0.0), [box(0.05, -0.5, 1.0, 0.5)], True),
    ("clear by 1 mm", (0.0, 0.0, 0.0), [box(FRONT + 0.001, -0.5, 1.0, 0.5)], False),
    ("inside a big block (no edge crossing)", (0.0, 0.0, 0.0), [box(-1.0, -1.0, 1.0, 1.0)], False),
    ("block inside the plate", (0.0, 0.0, 0.0), [box(-0.01, -0.01, 0.01, 0.01)], False),
    ("rotated, touching a side", (0.0, 0.0, np.pi / 2), [box(-0.5, FRONT, 0.5, 1.0)], True),
    # an obstacle's corner on a plate edge: the crossing lies at the end of the *obstacle's* edge (u_b = 0)
    ("obstacle corner touching the plate's left side", (0.0, 0.0, 0.0),
     [np.array([[0.0, SIDE], [0.05, 0.2], [-0.05, 0.2]])], True),
    ("obstacle corner 1 mm off the left side", (0.0, 0.0, 0.0),
     [np.array([[0.0, SIDE + 0.001], [0.05, 0.2], [-0.05, 0.2]])], False),
]


def problems(collides) -> list:
    out = []
    for name, pose, obstacles, want in CASES:
        xs, ys = transform_fast(pose, BASE_PLATE)
        if collides(list(zip(xs, ys, strict=True)), obstacles) != want:
            out.append(name)
    return out


def simiam_fast(plate, obstacles):
    """The culled test, and the all-pairs one where it leaves the answer to the last bits."""
    xs = [p[0] for p in plate]
    ys = [p[1] for p in plate]
    verdict = plate_collides(xs, ys, ObstacleEdges(obstacles).polygons)
    return simiam_exact(plate, obstacles) if verdict is None else verdict


def simiam_exact(plate, obstacles):
    return plate_collides_exact(plate, ObstacleEdges(obstacles).surfaces)


def test_fast_path_leaves_only_touching_to_the_exact_test():
    """A vertex exactly on an edge is decided by the last bits of the placement: the culled test leaves it
    undecided (None); everything clear by a millimetre or crossing it decides itself."""
    undecided = []
    for name, pose, obstacles, _ in CASES:
        xs, ys = transform_fast(pose, BASE_PLATE)
        if plate_collides(xs, ys, ObstacleEdges(obstacles).polygons, tolerance(1e-16, 5.0)) is None:
            undecided.append(name)
    assert undecided == [name for name, *_ in CASES if "touching" in name]


@pytest.mark.parametrize("collides", [simiam_fast, simiam_exact], ids=["fast", "exact"])
def test_collision_cases(collides):
    assert problems(collides) == []


@pytest.mark.parametrize("name", ["plate_collides", "plate_collides_with_containment"])
def test_collision_check_catches(name):
    assert problems(getattr(wrong("collision_strict"), name))
