"""Issue 32: the worker writes a step's answer record straight from the supervisor
(grader.inside.record_writer). What it writes must be exactly `encode_answer(rid, LocalBrain.answer())`,
or, where that is None, `LocalBrain.answer()` itself (then sent as JSON): for the course's solutions and
stubs over whole runs, and for supervisors holding anything a student's code can leave in them. Each value
is read once, in LocalBrain.answer's order (a property that counts its reads sees the same counts).

The wrong version sandbox_wrong/careless_writer.py (no check that the state is exactly a str) is caught
by `_differences`.
"""

from __future__ import annotations

import math
import types
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sandbox_wrong.careless_writer import careless_source

from grader.inside import record_writer
from grader.inside.step_record import layout_for
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.signals import declared, read_plan, week_signals
from simiam.simulator import Simulator
from simiam.world import load_world

REPO = Path(__file__).resolve().parents[2]


def _same(a: object, b: object) -> bool:
    """Equal, NaN equal to NaN, and of the same types all the way down (1 is not 1.0 here)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))  # type: ignore[arg-type]
    if isinstance(a, dict):
        return list(a) == list(b) and all(_same(a[k], b[k]) for k in a)  # type: ignore[index]
    return a == b


def _differences(layout, reference_brain, written_brain, rid: int, write) -> str:
    """'' when `write(rid)` (for `written_brain`) is what encoding `reference_brain.answer()` gives, or
    raises what it raises (the worker then answers with the student's error)."""
    try:
        answer = reference_brain.answer()
    except Exception as exc:  # noqa: BLE001 - a student's object may raise anything
        try:
            write(rid)
        except type(exc) as again:
            return "" if str(again) == str(exc) else f"raised {again!r}, not {exc!r}"
        return f"expected {exc!r}, got an answer"
    expected = layout.encode_answer(rid, answer)
    got = write(rid)
    if expected is None:
        return "" if type(got) is dict and _same(got, answer) else f"expected JSON of {answer!r}, got {got!r}"
    return "" if got == expected else f"expected the record {expected!r}, got {got!r} (answer {answer!r})"


# ---- whole runs of the course's solutions and stubs --------------------------------------------------------
class _Twin:
    """Steps brain `a` (LocalBrain.step, which drives the run) and brain `b` (think, then the writer) on
    the same readings, and keeps every step where the two differ."""

    def __init__(self, a: LocalBrain, b: LocalBrain, layout) -> None:
        self.a, self.b, self.layout, self.k, self.wrong = a, b, layout, 0, []
        self.write = layout.writer(b)

    def step(self, readings: dict) -> dict:
        self.k += 1
        self.a.think(readings)
        self.b.think(readings)
        if wrong := _differences(self.layout, self.a, self.b, self.k, self.write):
            self.wrong.append(f"step {self.k}: {wrong}")
        return self.a.answer()


@pytest.mark.parametrize("week", [3, 4, 5, 6, 7])
@pytest.mark.parametrize("kind", ["solutions", "assignments"])
def test_the_writer_writes_what_the_encoder_gives_over_a_run(week, kind):
    declaration = get_week(week)
    folder = REPO / kind / f"week{week}"
    first, second = load_submission(folder, declaration), load_submission(folder, declaration)
    a, b = LocalBrain(first, declaration), LocalBrain(second, declaration)
    layout = layout_for(week_signals(declaration), len(declaration.spec.ir_mounts))
    twin = _Twin(a, b, layout)
    world = load_world(declaration.world)
    sim = Simulator(world, twin, declaration.spec, dt=declaration.dt, start=world.start,
                    signals=week_signals(declaration))
    trace = sim.run(min(declaration.seconds, 10.0))
    assert twin.k > 0 and twin.wrong == [], twin.wrong[:3]
    assert len(trace.steps["t"]) > 1
    first.unload()
    second.unload()


# ---- supervisors holding anything --------------------------------------------------------------------------
class _Unindexable:
    def __getitem__(self, i):
        raise ValueError("no")


class _Text(str):
    pass


class _Named:
    def __str__(self):
        return _Text("go_to_goal")


_ANY = st.sampled_from([
    None, 0.25, -0.0, math.nan, math.inf, 1e308, 3, True, np.float64(0.5), np.float32(1.5), np.int64(7),
    np.bool_(True), "left", "é" * 200, "x\ud800", [0.5, -1.5], [1.0], [0.5, "a"], (0.5, 0.25),
    np.array([0.5, -1.5]), np.array([[0.1] * 5, [0.2] * 5]), np.array([[0.1] * 5, [math.nan] * 5]),
    [[0.1] * 5, [0.2] * 5], [[0.1] * 4, [0.2] * 5], 2**70, -1, _Unindexable(),
    {"at_goal": True, "at_obstacle": np.bool_(False), "unsafe": 1, "obstacle_cleared": None,
     "progress_made": True, "sliding_left": False, "sliding_right": "yes"}])
_SPEED = st.sampled_from([0.5, -2.25, 3, np.float64(1.5), math.nan, "fast", None, True])
_STATE = st.sampled_from(["go_to_goal", "s" * 81, "é" * 81, "x\ud800", 7, _Named()])
_ESTIMATE = st.sampled_from([(0.1, 0.2, 0.3), [0.1, 0.2], (1, 2, 3), (np.float64(0.1), 0.2, math.inf),
                             (0.1, 0.2, 0.3, 0.4), ("a", 0.2, 0.3)])


class _FakeBrain(types.SimpleNamespace):
    """What LocalBrain.answer and the writer read of a brain: its robot, supervisor, signals and plan."""

    def answer(self) -> dict:
        return LocalBrain.answer(self)  # type: ignore[arg-type]


def _fake(layout, speeds, estimate, state, values) -> _FakeBrain:
    """A brain whose robot and supervisor hold the drawn values: the attribute each declared signal reads
    holds values[i], on the supervisor or on its current controller."""
    signals = declared(layout.names)
    holders = {"controller": types.SimpleNamespace(), "supervisor": types.SimpleNamespace()}
    for s, value in zip(signals, values, strict=True):
        setattr(holders[s.owner], s.attr, value)
    sup = holders["supervisor"]
    sup.current_controller = holders["controller"]
    sup.state_estimate = types.SimpleNamespace(unpack=lambda: estimate)
    sup.current_state = state
    robot = types.SimpleNamespace(vel_r=speeds[0], vel_l=speeds[1])
    return _FakeBrain(robot=robot, supervisor=sup, signals=signals, _n_ir=layout.n_ir,
                      _plan=read_plan(signals, layout.n_ir))


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from([3, 5, 6, 7]), st.tuples(_SPEED, _SPEED), _ESTIMATE, _STATE, st.data())
def test_the_writer_writes_what_the_encoder_gives_for_anything_a_supervisor_holds(week, speeds, estimate,
                                                                                 state, data):
    declaration = get_week(week)
    layout = layout_for(week_signals(declaration), len(declaration.spec.ir_mounts))
    values = data.draw(st.lists(_ANY, min_size=len(layout.names), max_size=len(layout.names)))
    reference, written = (_fake(layout, speeds, estimate, state, values) for _ in range(2))
    assert _differences(layout, reference, written, 5, layout.writer(written)) == ""


def test_every_value_is_read_once_in_the_answers_order():
    """A supervisor whose attributes log their reads: the writer reads what LocalBrain.answer reads, in
    the same order, each once."""
    declaration = get_week(7)
    layout = layout_for(week_signals(declaration), len(declaration.spec.ir_mounts))

    def logged(log: list) -> types.SimpleNamespace:
        class Logged(types.SimpleNamespace):
            def __getattribute__(self, name):
                if not name.startswith("__"):
                    log.append(name)
                return super().__getattribute__(name)

        base = _fake(layout, (0.5, 0.25), (0.1, 0.2, 0.3), "go_to_goal", [None] * len(layout.names))
        sup, ctl = Logged(**vars(base.supervisor)), Logged(**vars(base.supervisor.current_controller))
        sup.current_controller = ctl
        base.supervisor, base.robot = sup, Logged(**vars(base.robot))
        log.clear()
        return base

    answer_log: list[str] = []
    write_log: list[str] = []
    reference = logged(answer_log)
    reference.answer()
    written = logged(write_log)
    layout.writer(written)(1)
    assert write_log == answer_log and "fw_direction" in write_log


def test_the_test_catches_a_writer_that_takes_a_str_subclass_for_a_str(monkeypatch):
    declaration = get_week(3)
    layout = layout_for(week_signals(declaration), len(declaration.spec.ir_mounts))
    values = [0.25, [0.5, -1.5], [[0.1] * 5, [0.2] * 5], 0.5, 0.5]
    reference, written = (_fake(layout, (0.5, 0.25), (0.1, 0.2, 0.3), _Named(), values) for _ in range(2))
    assert _differences(layout, reference, written, 5, layout.writer(written)) == ""
    monkeypatch.setattr(record_writer, "writer_source", careless_source)
    careless = record_writer.compile_writer(layout, layout._caps, written)
    assert "expected JSON" in _differences(layout, reference, written, 5, careless)
