"""The one step loop (Simulator.run / run_steps, Fleet.run): the trace says how the run ended, and only
what a brain did ends it quietly."""

from __future__ import annotations

import pytest

from simiam.course.weeks import spec_for_week
from simiam.fleet import Fleet
from simiam.simulator import ConstantBrain, Simulator
from simiam.trace import Ending, EndReason, Trace
from simiam.world import load_world


class Timeout(Exception):
    """Stands for a per-step time limit (simiam run's StepTimeout, grade's StudentTimeout)."""


class FailsAt:
    """A brain that behaves for `k - 1` steps, then raises or answers `answer`."""

    def __init__(self, k, raise_=None, answer=None):
        self.k, self.raise_, self.answer, self.n = k, raise_, answer, 0

    def step(self, readings):
        self.n += 1
        if self.n == self.k:
            if self.raise_ is not None:
                raise self.raise_
            return self.answer
        return {"vel_r": 2.0, "vel_l": 2.0}


def _sim(brain, start=(0.0, 0.0, 0.0)):
    return Simulator(load_world("week3"), brain, spec_for_week(3), dt=0.05, start=start)


def test_time_up():
    trace = _sim(ConstantBrain(1.0, 1.0)).run(seconds=1.0)
    assert trace.ending == Ending(EndReason.TIME_UP, 20, pytest.approx(1.0)) and len(trace) == 21
    assert not trace.ending.broken


def test_collision_and_until():
    crash = _sim(ConstantBrain(8.0, 8.0), start=(1.2, 0.0, 0.0)).run(seconds=10.0)
    assert crash.ending.reason is EndReason.COLLISION and crash.ending.step == crash.collision["step"]
    until = _sim(ConstantBrain(4.0, 4.0)).run(seconds=10.0, until=lambda rec: rec.pose[0] > 0.1)
    assert until.ending.reason is EndReason.UNTIL and until.steps["x"][-1] > 0.1 >= until.steps["x"][-2]
    assert until.ending.t == until.steps["t"][-1]


@pytest.mark.parametrize("brain,reason,words", [
    (FailsAt(4, raise_=ZeroDivisionError("oops")), EndReason.BRAIN_ERROR, "ZeroDivisionError: oops"),
    (FailsAt(4, raise_=SystemExit(3)), EndReason.BRAIN_ERROR, "SystemExit: 3"),
    (FailsAt(4, raise_=Timeout()), EndReason.STUCK, "Timeout"),
    (FailsAt(4, answer={"vel_r": "fast", "vel_l": 1.0}), EndReason.INVALID_COMMAND, "vel_r must be a finite"),
    (FailsAt(4, answer=[1.0, 1.0]), EndReason.INVALID_COMMAND, "must be a dict"),
])
def test_a_broken_brain_ends_the_run_and_keeps_the_trace(brain, reason, words):
    trace = _sim(brain).run(seconds=2.0, stuck=(Timeout,))
    end = trace.ending
    assert end.reason is reason and end.broken and words in end.message
    assert end.step == 4 and end.t == pytest.approx(0.2) and len(trace) == 4  # the failed step is not a row
    assert end.error is not None and words.split(":")[0] in type(end.error).__name__ + str(end.error)
    back = Trace.from_json(trace.to_json()).ending
    assert back == end and back.error is None  # the exception stays in memory, the words go to JSON


def test_a_timeout_type_not_named_stuck_is_a_brain_error():
    assert _sim(FailsAt(2, raise_=Timeout())).run(seconds=1.0).ending.reason is EndReason.BRAIN_ERROR


def test_ctrl_c_and_simulator_bugs_are_not_swallowed():
    with pytest.raises(KeyboardInterrupt):
        _sim(FailsAt(2, raise_=KeyboardInterrupt())).run(seconds=1.0)

    sim = Simulator(load_world("week3"), ConstantBrain(1.0, 1.0), spec_for_week(3), dt=0.05)
    physics = sim._surfaces.step

    def buggy(pose):  # WRONG: a bug in the physics must not read as the student's error
        if sim.steps_taken == 3:
            raise ZeroDivisionError("physics bug")
        return physics(pose)

    sim._surfaces.step = buggy
    with pytest.raises(ZeroDivisionError, match="physics bug"):
        sim.run(seconds=1.0)


def test_fleet_runs_through_the_same_loop():
    spec = spec_for_week(3)
    world = load_world("week3")
    traces = Fleet(world, [(ConstantBrain(1.0, 1.0), spec, (0.0, 0.0, 0.0)),
                           (FailsAt(5, raise_=ValueError("bad")), spec, (0.0, 0.5, 0.0))], dt=0.05).run(2.0)
    assert len(traces) == 2 and traces[0].ending is traces[1].ending
    end = traces[0].ending
    assert end.reason is EndReason.BRAIN_ERROR and end.message == "robot 2: ValueError: bad"
    assert len(traces[0]) == len(traces[1]) == 5
    calm = Fleet(world, [(ConstantBrain(1.0, 1.0), spec, (0.0, 0.0, 0.0))], dt=0.05).run(1.0)
    assert calm[0].ending.reason is EndReason.TIME_UP and len(calm[0]) == 21


def test_an_old_trace_without_signals_or_ending_still_loads():
    import json
    from pathlib import Path

    data = json.loads((Path(__file__).parents[1] / "data/traces/week4_wander.json").read_text())
    assert "signals" not in data and "ending" not in data
    trace = Trace.from_json(data)
    assert trace.signal_names == ("theta_g", "u_ao", "ir_points_wf", "v", "w") and trace.ending is None
    assert "u_ao_y" in trace.csv_header() and len(trace.csv_rows()) == len(trace)
