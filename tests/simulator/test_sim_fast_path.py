"""The culled fast paths (collision, IR ranging) give results identical to the all-pairs exact paths."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from simiam.physics.collision import plate_collides, plate_collides_exact
from simiam.physics.ir_ranging import cone_range, cone_range_exact
from simiam.physics.segments import ObstacleEdges
from simiam.physics.transform import transform_fast
from simiam.robot.ir_sensor import mounted_cone
from simiam.robot.quickbot import BASE_PLATE, spec_for_week
from simiam.world import load_world

SPEC = spec_for_week(4)
CONES = [mounted_cone(m, SPEC.ir_max_range, SPEC.ir_spread) for m in SPEC.ir_mounts]
WORLDS = {name: ObstacleEdges(load_world(name).obstacles) for name in ("week4", "week5", "final")}

coord = st.floats(-1.7, 1.7, allow_nan=False)
heading = st.floats(-10.0, 10.0, allow_nan=False)


@settings(max_examples=400, deadline=None)
@given(st.sampled_from(sorted(WORLDS)), coord, coord, heading)
def test_fast_equals_exact(world, x, y, theta):
    obstacles = WORLDS[world]
    pose = (x, y, theta)
    xs, ys = transform_fast(pose, BASE_PLATE)
    plate = list(zip(xs, ys, strict=True))
    assert plate_collides(xs, ys, obstacles.polygons) == plate_collides_exact(plate, obstacles)
    for cone in CONES:
        xs, ys = transform_fast(pose, cone)
        fast = cone_range(xs, ys, obstacles.polygons, 0.04, 0.3)
        exact = cone_range_exact(list(zip(xs, ys, strict=True)), obstacles, 0.04, 0.3)
        assert fast == exact


def test_fast_equals_exact_near_walls():
    """A dense sweep along the final world's walls and obstacle faces, where culling matters most."""
    obstacles = WORLDS["final"]
    hits = 0
    for i in range(60):
        for j in range(12):
            pose = (-0.75 + 0.025 * i, 0.05 + 0.01 * j, 0.5 * j)
            xs, ys = transform_fast(pose, BASE_PLATE)
            assert plate_collides(xs, ys, obstacles.polygons) == plate_collides_exact(
                list(zip(xs, ys, strict=True)), obstacles)
            for cone in CONES:
                cx, cy = transform_fast(pose, cone)
                fast = cone_range(cx, cy, obstacles.polygons, 0.04, 0.3)
                hits += fast < 0.3
                assert fast == cone_range_exact(list(zip(cx, cy, strict=True)), obstacles, 0.04, 0.3)
    assert hits > 100  # the sweep really sees obstacles


SIM_WORLDS = {name: load_world(name) for name in ("week4", "final")}


@settings(max_examples=150, deadline=None)
@given(st.sampled_from(sorted(SIM_WORLDS)), coord, coord, heading)
def test_simulator_culling_equals_exact(world, x, y, theta):
    """The Simulator's per-step candidate selection (ObstacleEdges.near) drops nothing."""
    from simiam.simulator import ConstantBrain, Simulator

    sim = Simulator(SIM_WORLDS[world], ConstantBrain(0, 0), SPEC, start=(x, y, theta))
    obstacles = WORLDS[world]
    xs, ys = transform_fast((x, y, theta), BASE_PLATE)
    assert sim.touches_obstacle() == plate_collides_exact(list(zip(xs, ys, strict=True)), obstacles)
    for i, cone in enumerate(CONES):
        cx, cy = transform_fast((x, y, theta), cone)
        assert sim.ir_range[i] == cone_range_exact(list(zip(cx, cy, strict=True)), obstacles, 0.04, 0.3)
