"""Fleet: several robots in one world see each other with their IR cones and collide with each other's base
plates; one robot in a Fleet is exactly a Simulator. A Fleet that steps its robots apart is caught."""

from __future__ import annotations

import math

import pytest
from sim_helpers import wrong

from instructor_tools.reference_brains import AvoidObstaclesBrain
from simiam.course.weeks import spec_for_week
from simiam.fleet import Fleet
from simiam.simulator import ConstantBrain, Simulator
from simiam.world import World, load_world

SPEC = spec_for_week(4)
EMPTY = World("empty", [])


def head_on(fleet_cls) -> dict:
    """Two robots 0.4 m apart drive at each other at 0.2 m/s: when do they collide?"""
    fleet = fleet_cls(EMPTY, [(ConstantBrain(6.0, 6.0), SPEC, (0.0, 0.0, 0.0)),
                              (ConstantBrain(6.0, 6.0), SPEC, (0.4, 0.0, math.pi))], dt=0.05)
    for _ in range(60):
        records = fleet.step()
        if any(r.collided for r in records):
            return {"collided": [r.collided for r in records], "t": records[0].t,
                    "gap": records[1].pose[0] - records[0].pose[0]}
    return {"collided": [False, False]}


def facing(fleet_cls) -> tuple:
    """Robot 0 stands 0.15 m in front of robot 1's nose: the raw value robot 0's front sensor reads."""
    fleet = fleet_cls(EMPTY, [(ConstantBrain(0.0, 0.0), SPEC, (0.0, 0.0, 0.0)),
                              (ConstantBrain(0.0, 0.0), SPEC, (0.35, 0.0, math.pi))])
    return fleet.step()[0].ir_raw


def test_robots_collide_with_each_other():
    res = head_on(Fleet)
    assert res["collided"] == [True, True], res
    # the noses (0.0686 m ahead of each origin) meet when the origins are 0.137 m apart
    assert 0.137 - 0.02 < res["gap"] <= 0.1372, res


def test_robots_see_each_other():
    raw = facing(Fleet)
    # the other robot's nose is 0.218 m ahead of the front sensor (raw 194 on the axis; the cone's edges
    # meet the plate's slanted front edges a little farther away)
    assert raw[:2] == raw[3:] == (133, 133) and 180 < raw[2] < 200, raw
    alone = Simulator(EMPTY, ConstantBrain(0.0, 0.0), SPEC)
    assert alone.step().ir_raw[2] == 133


@pytest.mark.parametrize("check", [head_on, facing])
def test_a_fleet_of_strangers_is_caught(check):
    blind = wrong("fleet_blind").Fleet
    assert check(blind) != check(Fleet)


def test_one_robot_in_a_fleet_is_a_simulator():
    world = load_world("week4")
    fleet = Fleet(world, [(AvoidObstaclesBrain(SPEC), SPEC, (0.0, 0.0, 0.0))])
    sim = Simulator(world, AvoidObstaclesBrain(SPEC), SPEC)
    assert fleet.robots[0].last == sim.last
    for _ in range(600):
        assert fleet.step()[0] == sim.step()


def ir_at_the_crash(fleet_cls) -> tuple:
    """Robot 0 drives into the east wall while robot 1 drives toward the west wall, its front sensor reading
    a new value every step: robot 1's readings in the two steps before the crash and at the crash."""
    world = load_world("week3")
    fleet = fleet_cls(world, [(ConstantBrain(8.0, 8.0), SPEC, (1.2, 0.0, 0.0)),
                              (ConstantBrain(4.0, 4.0), SPEC, (-1.2, 0.0, math.pi))], dt=0.05)
    raws = [fleet.robots[1].ir_raw[2]]
    for _ in range(100):
        records = fleet.step()
        raws.append(records[1].ir_raw[2])
        if records[0].collided:
            assert not records[1].collided
            return tuple(raws[-3:])
    raise AssertionError("robot 0 never reached the wall")


def test_a_collision_freezes_every_robots_ir():
    """As the original's apply_physics: at the first collision it returns before any IR update."""
    before, last, at_crash = ir_at_the_crash(Fleet)
    assert 133 < before < last == at_crash, (before, last, at_crash)
    assert ir_at_the_crash(wrong("fleet_blind").Fleet)[2] != at_crash
