"""The culled fast paths (collision, IR ranging) decide as the all-pairs exact paths do, and the Simulator
answers as the original's Physics on the original's (fused) vertices."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from simiam.course.weeks import spec_for_week
from simiam.physics.collision import plate_collides, plate_collides_exact
from simiam.physics.ir_ranging import cone_range, cone_range_exact
from simiam.physics.precheck import span
from simiam.physics.segments import ObstacleEdges, tolerance
from simiam.physics.transform import transform_exact, transform_fast
from simiam.robot.ir_sensor import distance_to_raw, mounted_cone
from simiam.robot.quickbot import BASE_PLATE
from simiam.world import load_world

SPEC = spec_for_week(4)
CONES = [mounted_cone(m, SPEC.ir_max_range, SPEC.ir_spread) for m in SPEC.ir_mounts]
WORLDS = {name: ObstacleEdges(load_world(name).obstacles) for name in ("week4", "week5", "final")}

# placements within 1e-16 of the original's, against obstacles as large as the final world's walls
MARGINS = tolerance(1e-16, 8.0)

coord = st.floats(-1.7, 1.7, allow_nan=False)
heading = st.floats(-10.0, 10.0, allow_nan=False)


def decided_agree(pose, obstacles) -> int:
    """Asserts that every answer the fast paths give at `pose` is the exact paths' on the same vertices;
    returns how many they left undecided."""
    undecided = 0
    xs, ys = transform_fast(pose, BASE_PLATE)
    verdict = plate_collides(xs, ys, obstacles.polygons, MARGINS)
    if verdict is None:
        undecided += 1
    else:
        assert verdict == plate_collides_exact(list(zip(xs, ys, strict=True)), obstacles.surfaces)
    for cone in CONES:
        xs, ys = transform_fast(pose, cone)
        found = cone_range(xs, ys, obstacles.polygons, 0.04, 0.3, MARGINS)
        if found is None:
            undecided += 1
        else:
            assert found[0] == cone_range_exact(list(zip(xs, ys, strict=True)), obstacles.surfaces, 0.04, 0.3)
    return undecided


@settings(max_examples=400, deadline=None)
@given(st.sampled_from(sorted(WORLDS)), coord, coord, heading)
def test_fast_equals_exact(world, x, y, theta):
    decided_agree((x, y, theta), WORLDS[world])


def test_fast_equals_exact_near_walls():
    """A dense sweep along the final world's walls and obstacle faces, where culling matters most."""
    obstacles = WORLDS["final"]
    hits = undecided = 0
    for i in range(60):
        for j in range(12):
            pose = (-0.75 + 0.025 * i, 0.05 + 0.01 * j, 0.5 * j)
            undecided += decided_agree(pose, obstacles)
            for cone in CONES:
                cx, cy = transform_fast(pose, cone)
                found = cone_range(cx, cy, obstacles.polygons, 0.04, 0.3, MARGINS)
                hits += found is not None and found[0] < 0.3
    assert hits > 100  # the sweep really sees obstacles
    assert undecided == 0  # and the margins leave nothing to the exact path away from exact contact


SIM_WORLDS = {name: load_world(name) for name in ("week4", "final")}


@settings(max_examples=150, deadline=None)
@given(st.sampled_from(sorted(SIM_WORLDS)), coord, coord, heading)
def test_simulator_equals_the_original_on_fused_vertices(world, x, y, theta):
    """The Simulator's per-step candidate selection (ObstacleEdges.near) drops nothing, and its answers are
    the original's tests on the original's vertices (ranges to the rounding of the plain transform)."""
    from simiam.simulator import ConstantBrain, Simulator

    sim = Simulator(SIM_WORLDS[world], ConstantBrain(0, 0), SPEC, start=(x, y, theta))
    surfaces = WORLDS[world].surfaces
    xs, ys = transform_exact((x, y, theta), BASE_PLATE)
    plate = list(zip(xs, ys, strict=True))
    assert sim.touches_obstacle() == plate_collides_exact(plate, surfaces, span(BASE_PLATE))
    for i, cone in enumerate(CONES):
        cx, cy = transform_exact((x, y, theta), cone)
        want = cone_range_exact(list(zip(cx, cy, strict=True)), surfaces, 0.04, 0.3, span(cone))
        assert abs(sim.ir_range[i] - want) <= 1e-14
        assert sim.ir_raw[i] == distance_to_raw(want, SPEC.ir_mode)
