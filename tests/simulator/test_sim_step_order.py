"""The original's step order: move -> encoders -> brain (one-step-old IR) -> limit_speeds -> collision ->
IR only if no collision; one IR update at construction."""

from __future__ import annotations

import math

import pytest
from sim_helpers import wrong

from simiam.course.weeks import spec_for_week
from simiam.simulator import BrainError, ConstantBrain, Simulator, validate_command
from simiam.world import load_world


class Recorder(ConstantBrain):
    """Drives straight and keeps every reading it was given."""

    def __init__(self, vel: float) -> None:
        super().__init__(vel, vel)
        self.seen: list[dict] = []

    def step(self, readings: dict) -> dict:
        self.seen.append(readings)
        return super().step(readings)


def order_problems(sim_cls) -> list:
    """Drive at the east wall of the week-3 world; check what the brain saw against the state history."""
    out = []
    brain = Recorder(8.0)
    sim = sim_cls(load_world("week3"), brain, spec_for_week(3), dt=0.05, start=(1.05, 0.0, 0.0))
    history = [sim.last]
    for _ in range(40):
        history.append(sim.step())
        if sim.collided:
            break
    if history[1].pose != history[0].pose:
        out.append("the first step moved (speeds start at 0)")
    for k, seen in enumerate(brain.seen, start=1):
        if seen["ir_raw"] != list(history[k - 1].ir_raw):
            out.append(("IR not one step old", k))
        if tuple(seen["ticks"]) != history[k].ticks:
            out.append(("ticks not after this step's move", k))
        if seen["t"] != k * 0.05:
            out.append(("t", k))
    if len({tuple(h.ir_raw) for h in history}) < 3:
        out.append("the run never saw the IR change")
    return out


def test_step_order():
    assert order_problems(Simulator) == []


def test_step_order_check_catches_fresh_ir():
    assert order_problems(wrong("simulator_wrong_order").FreshIRSimulator)


def test_collision_stops_and_freezes_ir():
    sim = Simulator(load_world("week3"), ConstantBrain(8.0, 8.0), spec_for_week(3), dt=0.05,
                    start=(1.2, 0.0, 0.0))
    trace = sim.run(seconds=10.0)
    assert trace.collision is not None and trace.steps["collided"][-1] is True
    k = trace.collision["step"]
    assert len(trace) == k + 1 and trace.steps["collided"].count(True) == 1
    assert trace.steps["ir_raw"][-1] == trace.steps["ir_raw"][-2]  # no IR pass on the collision step
    assert trace.collision["pose"] == [trace.steps["x"][-1], trace.steps["y"][-1], trace.steps["theta"][-1]]
    assert sim.pose[0] + 0.0686 >= 1.4  # the plate reaches the right wall at x = 1.4


def test_run_continues_after_collision_when_asked():
    sim = Simulator(load_world("week3"), ConstantBrain(8.0, 8.0), spec_for_week(3), dt=0.05,
                    start=(1.2, 0.0, 0.0))
    trace = sim.run(seconds=2.0, stop_on_collision=False)
    assert len(trace) == 41 and trace.collision is not None


def test_until_stops_the_run():
    sim = Simulator(load_world("week3"), ConstantBrain(4.0, 4.0), spec_for_week(3))
    trace = sim.run(seconds=10.0, until=lambda rec: rec.ticks[0] >= 10)
    assert trace.steps["ticks_r"][-1] >= 10 > trace.steps["ticks_r"][-2]


def test_true_heading_is_not_wrapped():
    sim = Simulator(load_world("week3"), ConstantBrain(8.0, -8.0), spec_for_week(3), dt=0.05)
    sim.run(seconds=10.0)
    assert sim.pose[2] > 2 * math.pi * 5


def test_week1_thinks_before_moving():
    sim = Simulator(load_world("week1"), ConstantBrain(4.0, 4.0), spec_for_week(1), dt=0.05)
    assert sim.step().pose[0] > 0  # week 1's order: execute, then update_state


@pytest.mark.parametrize("command,match", [
    ({"vel_r": True, "vel_l": 0.0}, "vel_r"),
    ({"vel_r": 1.0, "vel_l": float("nan")}, "vel_l"),
    ({"vel_r": "1", "vel_l": 0.0}, "vel_r"),
    ({"vel_l": 0.0}, "vel_r"),
    ({"vel_r": 1.0, "vel_l": 0.0, "estimate": [0.0, 1.0]}, "estimate"),
    ({"vel_r": 1.0, "vel_l": 0.0, "estimate": [0.0, 1.0, float("inf")]}, "estimate"),
    ({"vel_r": 1.0, "vel_l": 0.0, "state": 3}, "state"),
    ([1.0, 0.0], "dict"),
])
def test_invalid_commands(command, match):
    with pytest.raises(BrainError, match=match):
        validate_command(command)


def test_valid_command_is_normalised():
    cmd = validate_command({"vel_r": 1, "vel_l": -2.5, "estimate": (0, 1, 2), "state": "go_to_goal",
                            "debug": {"v": 0.1, "w": float("nan"), "theta_g": None, "u_ao": [1, 2],
                                      "ir_points_wf": [[1, 2, 3, 4, 5], [1, 2, 3]], "extra": object()},
                            "junk": 1})
    assert cmd == {"vel_r": 1.0, "vel_l": -2.5, "estimate": [0.0, 1.0, 2.0], "state": "go_to_goal",
                   "debug": {"v": 0.1, "w": None, "theta_g": None, "u_ao": [1.0, 2.0], "ir_points_wf": None}}


def test_brain_error_reaches_the_caller():
    class Bad:
        def step(self, readings):
            return {"vel_r": float("inf"), "vel_l": 0.0}
    sim = Simulator(load_world("week3"), Bad(), spec_for_week(3))
    with pytest.raises(BrainError):
        sim.step()
