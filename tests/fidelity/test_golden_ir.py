"""IR readings against ir_readings.csv (every pose and sensor) in the final world built from
worlds/final.xml: raw exact, true distance to 1e-12 m, sensor apex positions to 1e-12 m."""

from __future__ import annotations

import pytest
from physics_golden import check_ir, wrong

from simiam.course.weeks import spec_for_week
from simiam.simulator import ConstantBrain, Simulator
from simiam.world import load_world

WORLD = load_world("final")
SPEC = spec_for_week(4)


def simulator_ranger(pose):
    sim = Simulator(WORLD, ConstantBrain(0.0, 0.0), SPEC, dt=0.05, start=pose)
    assert not sim.touches_obstacle(), f"pose {pose} is recorded as collision-free"
    return sim.ir_range, sim.ir_raw, sim.sensor_positions()


def test_ir_readings_match():
    res = check_ir(simulator_ranger)
    assert res["poses"] > 0
    assert res["raw_bad"] == [], res["raw_bad"][:5]
    assert res["max_distance_error"] <= 1e-12, res
    assert res["max_apex_error"] <= 1e-12, res


def test_ir_after_a_step_in_place():
    """As recorded: one step with zero speeds at each pose, then the physics pass: same readings."""
    def ranger(pose):
        sim = Simulator(WORLD, ConstantBrain(0.0, 0.0), SPEC, dt=0.05, start=pose)
        rec = sim.step()
        assert rec.pose == pose and not rec.collided
        return rec.ir_range, rec.ir_raw, sim.sensor_positions()
    res = check_ir(ranger)
    assert res["raw_bad"] == [] and res["max_distance_error"] <= 1e-12


@pytest.mark.parametrize("name", ["centre_ray", "bankers_round", "mirrored_mounts"])
def test_ir_check_catches(name):
    res = check_ir(getattr(wrong("ir_wrong"), name))
    assert res["raw_bad"] or res["max_distance_error"] > 1e-12 or res["max_apex_error"] > 1e-12
