"""Week 6 framework and solution: norm rounds as Octave did, Inputs carries direction and d_fw (and refuses a
misspelt side), the supervisor hands its fw_direction and d_fw to the controller, settings override them,
Simulator.set_pose keeps the stale first reading, and solutions/week6 with its own settings follows the
wall on either side for the original test's 90 s (laps, no collision)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from simiam.control import Inputs, Pose2D, RobotView, Supervisor, norm
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import ConstantBrain, Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
WEEK6 = get_week(6)


def test_norm_is_the_length():
    assert norm([3.0, 4.0]) == 5.0
    assert norm(np.array([0.0, 0.0])) == 0.0
    assert norm([0.0, -2.5]) == 2.5
    assert norm((1e-200, 1e-200)) == pytest.approx(math.sqrt(2) * 1e-200, rel=1e-15)  # scaled: no underflow
    assert math.isnan(norm([float("nan"), 1.0]))


def test_norm_rounds_as_octave_not_as_hypot():
    """A recorded u_fw_t (followwall_vectors.csv case 1) whose Octave norm differs from hypot by one ulp."""
    u = (0.30800946917109073, -0.14624637089245396)
    assert u[0] / norm(u) == 0.90334356337355493  # the recorded u_fw_tp
    assert u[0] / math.hypot(*u) != 0.90334356337355493


def test_inputs_carry_direction_and_d_fw():
    inputs = Inputs(v=0.1, direction="right", d_fw=0.2)
    assert (inputs.direction, inputs.d_fw) == ("right", 0.2)
    assert Inputs(direction="").direction == ""  # what the week-7 FSM sets; FollowWall takes it for left


@pytest.mark.parametrize("bad", ["rigth", "Right", None, 1])
def test_a_misspelt_direction_is_an_error_that_names_it(bad):
    with pytest.raises(ValueError, match="'left' or 'right'") as err:
        Inputs(direction=bad)
    assert repr(bad) in str(err.value) and "fw_direction" in str(err.value)


def test_supervisor_inputs_hand_over_fw_direction_and_d_fw():
    sup = Supervisor()
    sup.fw_direction, sup.d_fw = "right", 0.12
    inputs = sup.inputs()
    assert (inputs.direction, inputs.d_fw) == ("right", 0.12)
    sup.fw_direction = "up"
    with pytest.raises(ValueError, match="'up'"):
        sup.inputs()


def _brain(settings: dict | None = None, start=(0.0, 0.0, 0.0)) -> LocalBrain:
    sub = load_submission(ROOT / "solutions/week6", WEEK6)
    assert sub.ok, sub.errors
    return LocalBrain(sub, WEEK6, settings, start=start)


def test_settings_override_d_fw_and_fw_direction():
    sup = _brain({"d_fw": 0.2, "fw_direction": "right"}).supervisor
    assert (sup.d_fw, sup.fw_direction, sup.current_state) == (0.2, "right", "follow_wall")
    assert (_brain().supervisor.d_fw, _brain().supervisor.fw_direction) == (0.18, "left")


def _follow_wall(direction: str, raw: list[int], pose=(0.0, 0.0, 0.0)):
    sub = load_submission(ROOT / "solutions/week6", WEEK6)
    robot = RobotView(WEEK6.spec, sub)
    robot.update({"ticks": [0, 0], "ir_raw": raw})
    ctrl = sub.module("follow_wall").FollowWall()
    ctrl.execute(robot, Pose2D(*pose), Inputs(v=0.1, direction=direction, d_fw=0.15), 0.05)
    return ctrl


def test_empty_direction_follows_the_left_wall():
    raw = [400, 300, 200, 250, 500]
    left, empty = _follow_wall("left", raw), _follow_wall("", raw)
    assert np.array_equal(left.u_fw, empty.u_fw)
    assert not np.array_equal(left.u_fw, _follow_wall("right", raw).u_fw)


def test_set_pose_keeps_the_old_reading_until_the_first_step():
    sim = Simulator(load_world("week6"), ConstantBrain(0.0, 0.0), WEEK6.spec, dt=0.05)
    sim.set_pose((0.0, 0.0, math.pi))
    assert sim.pose == (0.0, 0.0, math.pi) and sim.start == (0.0, 0.0, math.pi)
    assert list(sim.ir_raw) == [296, 177, 133, 133, 133]  # seen from (0, 0, 0)
    sim.step()
    assert list(sim.ir_raw) == [133, 133, 133, 196, 296]
    with pytest.raises(ValueError, match="before the first step"):
        sim.set_pose((0.0, 0.0, 0.0))


@pytest.mark.parametrize(("direction", "theta0"), [("left", 0.0), ("right", math.pi)])
def test_solution_laps_without_touching_anything(direction, theta0):
    """The original tests 6.1/6.2 with the solution's own d_fw and v: three departures from the start disc
    within 90 s, no collision, and never closer than 0.1 m to a wall (IR range of a side sensor)."""
    brain = _brain({"fw_direction": direction}, start=(0.0, 0.0, theta0))
    sim = Simulator(load_world("week6"), brain, WEEK6.spec, dt=0.05)
    sim.set_pose((0.0, 0.0, theta0))
    laps, armed = 0, True
    for _ in range(1800):
        rec = sim.step()
        assert not rec.collided, rec.step
        r = math.hypot(rec.pose[0], rec.pose[1])
        if armed and r > 0.1:
            laps, armed = laps + 1, False
        elif r < 0.1:
            armed = True
        if laps > 2:
            break
    assert laps > 2


def test_the_estimate_setting_starts_the_estimate_where_the_robot_is():
    """The original week-6 tests set the estimate with the true pose; the runs do it with `estimate`."""
    sup = _brain({"estimate": [0.0, 0.0, math.pi]}).supervisor
    assert sup.state_estimate.unpack() == (0.0, 0.0, math.pi)


@pytest.mark.parametrize("bad", [[0.0, 0.0], [0.0, 0.0, float("nan")], "0 0 0", [0.0, 0.0, None]])
def test_a_malformed_estimate_setting_is_refused_clearly(bad):
    with pytest.raises(ValueError, match="three finite numbers"):
        _brain({"estimate": bad})
