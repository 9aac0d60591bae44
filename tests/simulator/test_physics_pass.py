"""The one physics pass of a lone robot's step (RobotSurfaces.step): the same verdict, ranges and raw
values, bit for bit, as `collides` then `sense`, and as placing every IR cone (the pass before issue 24
placed all five whenever an obstacle was near). A cull that drops what a cone's width reaches is caught."""

from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st
from sim_helpers import wrong

from simiam.course.weeks import spec_for_week
from simiam.physics.robot_surfaces import RobotSurfaces
from simiam.world import load_world

SPEC = spec_for_week(4)
WORLDS = {name: load_world(name).obstacles for name in ("week4", "week6", "final")}


def every_cone_placed(obstacles) -> RobotSurfaces:
    """The same surfaces with capsules wide enough to meet every nearby box: each cone is placed."""
    surfaces = RobotSurfaces(SPEC, obstacles)
    surfaces._capsules = [(ax, ay, tx, ty, math.inf) for ax, ay, tx, ty, _ in surfaces._capsules]
    return surfaces


def bits(answer) -> list:
    return [v.hex() if isinstance(v, float) else v for v in answer]


def answers(surfaces: RobotSurfaces, pose) -> tuple:
    collided, ranges, raws = surfaces.step(pose)
    return collided, None if ranges is None else bits(ranges), raws


def sweep(world: str):
    """Poses along the final world's walls and around week 4's and 6's obstacles, every eighth turn and
    the axes' headings (where a cone's box is thinnest)."""
    obstacles = WORLDS[world]
    xs = [p[0] for ob in obstacles for p in ob]
    ys = [p[1] for ob in obstacles for p in ob]
    for i in range(36):
        for j in range(24):
            x = min(xs) + (max(xs) - min(xs)) * i / 35
            y = min(ys) + (max(ys) - min(ys)) * j / 23
            for k in range(8):
                yield (x, y, k * math.pi / 4)


def test_one_pass_is_collides_then_sense_and_every_cone_placed():
    seen = 0
    for world, obstacles in WORLDS.items():
        surfaces = RobotSurfaces(SPEC, obstacles)
        wide = every_cone_placed(obstacles)
        for pose in sweep(world):
            got = answers(surfaces, pose)
            assert got == answers(wide, pose), pose
            collided = surfaces.collides(pose)
            assert got[0] == collided
            if not collided:
                ranges, raws = surfaces.sense(pose)
                assert got[1:] == (bits(ranges), raws), pose
                seen += any(r < SPEC.ir_max_range for r in ranges)
    assert seen > 500  # the sweep really sees obstacles


@settings(max_examples=300, deadline=None)
@given(st.sampled_from(sorted(WORLDS)), st.floats(-2.0, 2.0), st.floats(-2.0, 2.0), st.floats(-10.0, 10.0))
def test_one_pass_anywhere(world, x, y, theta):
    pose = (x, y, theta)
    obstacles = WORLDS[world]
    assert answers(RobotSurfaces(SPEC, obstacles), pose) == answers(every_cone_placed(obstacles), pose)


def test_a_cull_without_the_cones_width_is_caught():
    thin = wrong("capsule_thin").thin
    differ = 0
    for world, obstacles in WORLDS.items():
        surfaces = thin(RobotSurfaces(SPEC, obstacles))
        wide = every_cone_placed(obstacles)
        differ += sum(answers(surfaces, pose) != answers(wide, pose) for pose in sweep(world))
    assert differ > 0


def walks(world: str):
    """A robot's poses driving from the middle of the world out to its walls in 1 cm steps, turning."""
    for k in range(16):
        heading = k * math.pi / 8 + 0.1
        for i in range(200):
            x, y = -0.9 + 0.01 * i * math.cos(heading), -0.9 + 0.01 * i * math.sin(heading)
            yield (x, y, heading + 0.002 * i)


def walk_differs(world: str) -> int:
    """How many poses of the walks the one pass (with its clear square, carried from pose to pose)
    answers otherwise than `collides` then `sense` (which look everything up every time)."""
    surfaces = RobotSurfaces(SPEC, WORLDS[world])
    differ = 0
    for pose in walks(world):
        collided, ranges, raws = surfaces.step(pose)
        want = surfaces.collides(pose)
        if not want:
            want_ranges, want_raws = surfaces.sense(pose)
            differ += (collided, bits(ranges), raws) != (False, bits(want_ranges), want_raws)
        else:
            differ += not collided
    return differ


def test_the_clear_square_holds_while_driving_at_walls():
    for world in WORLDS:
        assert walk_differs(world) == 0
        surfaces = RobotSurfaces(SPEC, WORLDS[world])
        skipped = 0
        for pose in walks(world):
            cx, cy, gap = surfaces._clear
            skipped += abs(pose[0] - cx) <= gap and abs(pose[1] - cy) <= gap
            surfaces.step(pose)
        assert skipped > 500  # the square really saves look-ups


def test_a_clear_square_that_forgets_the_cones_reach_is_caught(monkeypatch):
    wrong("clear_square_no_reach").install(monkeypatch)
    assert sum(walk_differs(world) for world in WORLDS) > 0
