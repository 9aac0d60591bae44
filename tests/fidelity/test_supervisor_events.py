"""The Supervisor base from week 5 on: the obstacle events and their thresholds, switch counting with the
new controller's reset, Octave's norm in at_goal, and unknown state or event names, which the original
silently ignored, named with the student's file and line."""

from __future__ import annotations

import csv
import inspect
import math
from pathlib import Path

import mistakes
import pytest
from physics_golden import GOLDEN

from simiam.control import Controller, Stop, Supervisor
from simiam.control.local_brain import LocalBrain
from simiam.control.norm import norm
from simiam.control.supervisor import UnknownNameError
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week

READINGS = {"t": 0.05, "dt": 0.05, "ticks": [0, 0], "ir_raw": [133, 133, 133, 133, 133]}

WEEK5 = get_week(5)


class _Robot:
    """Just what the events read: five IR distances."""

    def __init__(self, distances) -> None:
        self.distances = list(distances)

    def get_ir_distances(self):
        return self.distances


class _Memory(Controller):
    def execute(self, robot, state_estimate, inputs, dt):
        self.E_k += 1.0
        self.e_k_1 = 0.5
        return 0.0, 0.0


def _supervisor(distances=(0.3,) * 5) -> Supervisor:
    sup = Supervisor()
    sup.robot = _Robot(distances)
    sup.add_controller(Stop())
    sup.add_controller(_Memory("go_to_goal"))
    sup.add_controller(_Memory("avoid_obstacles"))
    return sup


@pytest.mark.parametrize(("distances", "at_obstacle", "unsafe", "cleared"), [
    ((0.3, 0.3, 0.3, 0.3, 0.3), False, False, True),
    ((0.3, 0.3, 0.3, 0.3, 0.2499), True, False, False),     # a side sensor counts (all five do)
    ((0.2499, 0.3, 0.3, 0.3, 0.3), True, False, False),
    ((0.3, 0.3, 0.25, 0.3, 0.3), False, False, False),      # strict: at d_at_obs is neither
    ((0.3, 0.0999, 0.3, 0.3, 0.3), True, True, False),
    ((0.3, 0.3, 0.3, 0.10, 0.3), True, False, False),       # strict: at d_unsafe is not unsafe
    ((0.2501,) * 5, False, False, True),
])
def test_obstacle_events_use_all_five_sensors_and_strict_thresholds(distances, at_obstacle, unsafe, cleared):
    sup = _supervisor(distances)
    assert (sup.d_at_obs, sup.d_unsafe) == (0.25, 0.10)  # the sp14 week-5 release's thresholds
    got = (sup.check_event("at_obstacle"), sup.check_event("unsafe"), sup.check_event("obstacle_cleared"))
    assert got == (at_obstacle, unsafe, cleared)


def test_events_follow_the_thresholds_a_supervisor_sets():
    sup = _supervisor((0.3, 0.3, 0.11, 0.3, 0.3))
    assert not sup.check_event("unsafe")
    sup.d_unsafe = 0.12
    sup.d_at_obs = 0.05
    assert sup.check_event("unsafe") and not sup.check_event("at_obstacle")


def test_switches_are_counted_and_reset_the_new_controller_only():
    sup = _supervisor()
    sup.switch_to_state("go_to_goal")
    assert sup.switch_count == 0  # the first state is no switch
    sup.execute_controller(sup.inputs(), 0.05)
    sup.switch_to_state("go_to_goal")
    assert sup.switch_count == 0 and sup.controllers["go_to_goal"].E_k == 1.0  # no switch, memory kept
    sup.switch_to_state("avoid_obstacles")
    sup.execute_controller(sup.inputs(), 0.05)
    assert sup.switch_count == 1 and sup.controllers["go_to_goal"].E_k == 1.0
    sup.switch_to_state("go_to_goal")
    assert sup.switch_count == 2
    assert (sup.controllers["go_to_goal"].E_k, sup.controllers["go_to_goal"].e_k_1) == (0.0, 0.0)
    assert sup.controllers["avoid_obstacles"].E_k == 1.0


def test_the_initial_state_of_a_run_counts_as_the_original_tests_did():
    """Test 5.1 asks for ao_and_gtg, where the supervisor already is (0 switches); 5.2 for go_to_goal (1)."""
    sub = load_submission(Path(__file__).resolve().parents[2] / "solutions/week5", WEEK5)
    assert LocalBrain(sub, WEEK5, {"state": "ao_and_gtg"}).supervisor.switch_count == 0
    assert LocalBrain(sub, WEEK5, {"state": "go_to_goal"}).supervisor.switch_count == 1


def test_an_unknown_event_names_the_callers_file_and_line_and_the_closest_name():
    sup = _supervisor()
    line = inspect.currentframe().f_lineno + 2
    with pytest.raises(UnknownNameError) as err:
        sup.check_event("at_obstacles")
    message = str(err.value)
    assert message.startswith(f"{Path(__file__).name}, line {line}: no event exists with name 'at_obstacles'")
    assert "did you mean 'at_obstacle'?" in message and "obstacle_cleared" in message


def test_a_name_that_is_not_a_string_is_refused_clearly():
    sup = _supervisor()
    with pytest.raises(UnknownNameError, match="a state name is a string such as 'stop', not int 3"):
        sup.switch_to_state(3)
    wanted = r"an event name is a string such as 'at_goal', not list \['at_goal'\]"
    with pytest.raises(UnknownNameError, match=wanted):
        sup.check_event(["at_goal"])


def test_an_event_in_other_capitals_is_suggested_even_where_difflib_finds_it_too_far():
    """'AT_OBSTACLE' is only 0.09 like 'at_obstacle' by difflib's ratio, under its 0.6 cutoff: the
    capitals alone differ."""
    with pytest.raises(UnknownNameError) as err:
        _supervisor().check_event("AT_OBSTACLE")
    assert "did you mean 'at_obstacle'?" in str(err.value)


def test_a_misspelt_state_in_the_students_file_is_named_with_its_line(tmp_path):
    """The original printed "no state exists with name ..." and kept the old controller running."""
    folder = mistakes.build("submissions", "week5_state_typo", tmp_path, 5)
    line = next(k for k, text in enumerate((folder / "qb_supervisor.py").read_text().splitlines(), 1)
                if '"avoid_obstacle")' in text)
    sub = load_submission(folder, WEEK5)
    assert sub.ok, sub.errors  # it loads: the mistake shows only when that branch runs
    brain = LocalBrain(sub, WEEK5, {"is_blending": False, "d_unsafe": 1.0})  # every reading is unsafe
    with pytest.raises(UnknownNameError) as err:
        brain.step(READINGS)
    wanted = f"qb_supervisor.py, line {line}: no state exists with name 'avoid_obstacle'"
    assert str(err.value).startswith(wanted)
    assert "did you mean 'avoid_obstacles'?" in str(err.value)


def test_a_wrong_name_from_the_settings_is_not_blamed_on_the_student():
    sub = load_submission(Path(__file__).resolve().parents[2] / "solutions/week5", WEEK5)
    with pytest.raises(UnknownNameError) as err:
        LocalBrain(sub, WEEK5, {"state": "follow_wall"})
    assert str(err.value).startswith("no state exists with name 'follow_wall'")


def test_at_goal_measures_with_octaves_norm():
    """u_fw_tp = u_fw_t / norm(u_fw_t) in the recorded FollowWall vectors: norm reproduces every row,
    math.hypot (the wrong version: the port's first at_goal) misses some in the last bit."""
    with (GOLDEN / "followwall_vectors.csv").open() as f:
        rows = [r for r in csv.DictReader(f) if (float(r["u_fw_t_x"]), float(r["u_fw_t_y"])) != (0.0, 0.0)]

    def misses(length) -> int:
        out = 0
        for r in rows:
            t = (float(r["u_fw_t_x"]), float(r["u_fw_t_y"]))
            out += (t[0] / length(t), t[1] / length(t)) != (float(r["u_fw_tp_x"]), float(r["u_fw_tp_y"]))
        return out

    assert len(rows) >= 50 and misses(norm) == 0 and misses(lambda t: math.hypot(*t)) > 0
    sup = _supervisor()
    sup.goal = (0.0, 0.05)
    sup.d_stop = 0.05
    assert not sup.check_event("at_goal")  # exactly d_stop away: not yet
    sup.goal = (0.0, 0.0499)
    assert sup.check_event("at_goal")
