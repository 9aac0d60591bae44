"""LocalBrain and the Supervisor base: the Seam-1 command, settings overrides, at_goal on the estimate."""

from __future__ import annotations

import math
import types
from pathlib import Path

import pytest

from simiam.control import RobotView
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week, spec_for_week
from simiam.simulator import Simulator, validate_command
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
READINGS = {"t": 0.033, "dt": 0.033, "ticks": [0, 0], "ir_raw": [133, 133, 133, 133, 133]}


def _brain(week: int, settings: dict | None = None) -> LocalBrain:
    sub = load_submission(ROOT / f"solutions/week{week}", week)
    assert sub.ok, sub.errors
    return LocalBrain(sub, get_week(week), settings)


def test_command_has_the_seam_shape_and_plain_floats():
    cmd = _brain(4).step(READINGS)
    assert set(cmd) == {"vel_r", "vel_l", "estimate", "state", "debug"}
    assert set(cmd["debug"]) == {"v", "w", "theta_g", "u_ao", "ir_points_wf"}
    assert cmd["state"] == "avoid_obstacles"
    assert type(cmd["vel_r"]) is float and type(cmd["vel_l"]) is float  # not numpy scalars
    assert all(type(c) is float for c in cmd["estimate"])
    assert len(cmd["debug"]["u_ao"]) == 2 and [len(r) for r in cmd["debug"]["ir_points_wf"]] == [5, 5]
    assert validate_command(cmd)["vel_r"] == cmd["vel_r"]


def test_settings_override_the_students_values():
    brain = _brain(4, {"v": 0.2, "goal": [1, 1], "d_stop": 0.1, "theta_d": 0.3, "state": "go_to_goal",
                       "gains": {"go_to_goal": {"Kp": 4, "Ki": 0.01, "Kd": 0.01}}})
    sup = brain.supervisor
    assert (sup.v, sup.goal, sup.d_stop, sup.theta_d) == (0.2, (1, 1), 0.1, 0.3)
    assert sup.current_state == "go_to_goal"
    assert (sup.controllers["go_to_goal"].Kp, sup.controllers["go_to_goal"].Kd) == (4, 0.01)
    cmd = brain.step(READINGS)
    assert cmd["debug"]["theta_g"] == pytest.approx(math.pi / 4)
    assert cmd["debug"]["v"] == 0.2 and cmd["debug"]["u_ao"] is None


def test_top_level_gains_are_accepted_and_unknown_controllers_refused():
    assert _brain(3, {"go_to_goal": {"Kp": 7}}).supervisor.controllers["go_to_goal"].Kp == 7
    with pytest.raises(ValueError, match="no controller"):
        _brain(3, {"gains": {"follow_wall": {"Kp": 1}}})
    with pytest.raises(ValueError, match="no state"):
        _brain(3, {"state": "follow_wall"})


@pytest.mark.parametrize(("settings", "words"), [
    ({"v": 0.15, "fw_directon": "right"},
     "the settings of this run: unknown setting 'fw_directon' (did you mean 'fw_direction'?); the settings "
     "are, closest first: fw_direction"),
    ({"Goal": [1, 1]}, "unknown setting 'Goal' (did you mean 'goal'?)"),
    ({"gains": {"go_to_goal": {"kp": 4}}}, "the gains of go_to_goal: unknown gain 'kp' (did you mean 'Kp'?); "
                                           "the gains are, closest first: Kp, "),
    ({"go_to_goal": {"K_d": 4}}, "unknown gain 'K_d' (did you mean 'Kd'?)"),
])
def test_a_misspelt_setting_or_gain_is_refused_not_set(settings, words):
    """Set and never read, a misspelt setting would leave the student's own value in force: refused, with
    the name it most likely meant and the known ones, closest first (the week's settings, the student's
    controllers; a controller's own numbers for its gains)."""
    with pytest.raises(ValueError) as refused:
        _brain(6 if "fw_directon" in settings else 3, settings)
    assert words in str(refused.value)


def test_at_goal_uses_the_estimate_not_the_true_pose():
    """Start the estimate at the goal: the week-3 supervisor stops at once, whatever the true pose."""
    sub = load_submission(ROOT / "solutions/week3", 3)
    brain = LocalBrain(sub, get_week(3), {"goal": (0.5, 0.5)}, start=(0.5, 0.5, 0.0))
    assert brain.step(READINGS)["state"] == "stop"
    assert _brain(3, {"goal": (0.5, 0.5)}).step(READINGS)["state"] == "go_to_goal"


def test_stop_state_reports_no_reference_heading():
    brain = _brain(3, {"state": "stop"})
    cmd = brain.step(READINGS)
    assert cmd["debug"]["theta_g"] is None and (cmd["vel_r"], cmd["vel_l"]) == (0.0, 0.0)


def _reachable(root) -> list:
    """Every object student code can reach from `root` through attributes and containers (modules,
    classes and functions are not followed: they are code, not state)."""
    seen: dict[int, object] = {}
    todo = [root]
    while todo:
        obj = todo.pop()
        if id(obj) in seen or isinstance(obj, (type, types.ModuleType, types.FunctionType,
                                               types.MethodType, types.BuiltinFunctionType)):
            continue
        seen[id(obj)] = obj
        if isinstance(obj, dict):
            todo += list(obj.keys()) + list(obj.values())
        elif isinstance(obj, (list, tuple, set)):
            todo += list(obj)
        elif hasattr(obj, "tolist"):
            todo.append(obj.tolist())
        else:
            todo += list(getattr(obj, "__dict__", {}).values())
            todo += [getattr(obj, s) for s in getattr(type(obj), "__slots__", ()) if hasattr(obj, s)]
    return list(seen.values())


def true_pose_leaks(make_view) -> list:
    """Drive the week-4 solution for 3 s; what of the true state the robot handed to student code reaches:
    the Simulator itself, or the true x / y as a number."""
    sub = load_submission(ROOT / "solutions/week4", 4)
    brain = LocalBrain(sub, get_week(4))
    sim = Simulator(load_world("week4"), brain, spec_for_week(4), dt=0.05)
    brain.robot = brain.supervisor.robot = make_view(sub, sim)
    sim.run(3.0)
    x, y, _ = sim.pose
    assert math.hypot(x, y) > 0.1  # it moved, so the true position is not a start value
    return [o for o in _reachable(brain.supervisor)
            if o is sim or (type(o) is float and o in (x, y))]


class _LeakyRobotView(RobotView):
    """WRONG: keeps a handle on the simulator (as a careless `robot.parent` would)."""

    def __init__(self, spec, sub, sim):
        super().__init__(spec, sub)
        self.parent = sim


def test_student_code_cannot_reach_the_true_pose():
    assert true_pose_leaks(lambda sub, sim: RobotView(spec_for_week(4), sub)) == []


def test_a_leaking_robot_is_caught():
    assert true_pose_leaks(lambda sub, sim: _LeakyRobotView(spec_for_week(4), sub, sim))
