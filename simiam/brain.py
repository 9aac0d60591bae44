"""Seam 1, typed: what a Brain reads each step, what it answers, and the one place that answer is checked.

A Brain is anything with `step(readings) -> command`: the student's supervisor in this process
(`simiam.control.local_brain.LocalBrain`), the same behind the sandbox's pipe (`RemoteBrain`), or a
trusted test double. Only plain values cross: `Readings` in, `Command` out. The simulator passes every
command through `validate_command` before it uses any of it, whoever the brain is (a `Checked` command
was checked by the same rules where the grader decoded it, and passes as it is).
"""

from __future__ import annotations

from typing import Any, Protocol, TypedDict, cast

from simiam.robot.quickbot import IR_MOUNTS
from simiam.signals import WEEKS_1_TO_4, Plan, Signal, clean_debug, declared, real

STATE_CHARS = 80  # a state name (a student picks it; it is shown in the replay, the report and the terminal)


class Readings(TypedDict):
    """One step's sensor values: simulated time `t` and step `dt` (s), cumulative encoder `ticks`
    [right, left], and `ir_raw`, one raw ADC value per IR sensor (as many as the robot spec mounts)."""

    t: float
    dt: float
    ticks: list[int]
    ir_raw: list[int]


class Command(TypedDict):
    """One step's answer: wheel speeds `vel_r`, `vel_l` (rad/s, before the robot's limits), the brain's
    own pose `estimate` [x, y, theta] or None, the running controller's `state` name or None, and
    `debug`: the declared signals (simiam.signals), only ever plotted."""

    vel_r: float
    vel_l: float
    estimate: list[float] | None
    state: str | None
    debug: dict[str, Any]


class Brain(Protocol):
    """What drives the robot: plain readings in, a plain command out. The answer is typed `Any` on
    purpose: whatever a brain returns is checked by `validate_command` before anything uses it."""

    def step(self, readings: Readings) -> Any: ...


def _estimate(est: Any) -> list[float]:
    if not (isinstance(est, (list, tuple)) and len(est) == 3 and all(real(c) for c in est)):
        raise BrainError(f"estimate must be three finite numbers (x, y, theta), got {est!r:.80}")
    return [float(c) for c in est]


class BrainError(Exception):
    """The brain returned something that is not a valid command."""


class Checked(dict):
    """A command that trusted code has already made exactly what `validate_command` returns for it, for
    the signals and IR count in `of` ((signals, n_ir), as validate_command takes them): validate_command
    returns it as it is when they are its own, and checks it like any other dict otherwise.

    Made only by the grader's decoder of step records (grader.inside.step_record, in the grading
    process), after it found every value already canonical: finite doubles, short strings, counts and
    points within their rules. Nothing a brain returns as a value is ever one: the sandbox sends bytes,
    and a LocalBrain builds plain dicts.
    """

    __slots__ = ("of",)
    of: tuple[tuple[Signal, ...], int]


class ConstantBrain:
    """A trusted brain that requests the same wheel speeds every step (tests, benchmarks)."""

    def __init__(self, vel_r: float, vel_l: float) -> None:
        self.vel_r = vel_r
        self.vel_l = vel_l

    def step(self, readings: Readings) -> Command:
        return {"vel_r": self.vel_r, "vel_l": self.vel_l, "estimate": None, "state": "constant", "debug": {}}


_DEFAULT = declared(WEEKS_1_TO_4)


def validate_command(command: Any, signals: tuple[Signal, ...] = _DEFAULT, n_ir: int = len(IR_MOUNTS),
                     plan: Plan | None = None) -> Command:
    """Check and normalise a brain's command; raises BrainError with a readable message.

    vel_r / vel_l must be finite real numbers (bool is rejected); estimate is None or three finite numbers;
    state a string (or None), cut to STATE_CHARS. Debug values go through simiam.signals.clean_debug:
    every declared signal is present, a missing or malformed one is None, unknown names are dropped.
    `n_ir` (the robot's IR sensor count) sizes the points signals; the defaults are weeks 1-4's. The
    simulator passes `plan` (simiam.signals.debug_plan) worked out once per run.
    """
    if type(command) is Checked and command.of == (signals, n_ir):  # validated when it was decoded
        return cast(Command, command)
    if not isinstance(command, dict):
        raise BrainError(f"the command must be a dict, got {type(command).__name__}")
    get = command.get
    vel_r = get("vel_r")
    if type(vel_r) is not float or vel_r - vel_r != 0.0:  # not the common case: a finite float, kept as is
        vel_r = _speed("vel_r", vel_r)
    vel_l = get("vel_l")
    if type(vel_l) is not float or vel_l - vel_l != 0.0:
        vel_l = _speed("vel_l", vel_l)
    est = get("estimate")
    if type(est) is list and len(est) == 3:
        x, y, theta = est
        if type(x) is float and type(y) is float and type(theta) is float:  # the common case
            total = x + y + theta  # one finiteness test for the three; an overflowing sum: the long way
            est = [x, y, theta] if total - total == 0.0 else _estimate(est)
        else:
            est = _estimate(est)
    elif est is not None:
        est = _estimate(est)
    state = get("state")
    if state is not None and not isinstance(state, str):
        raise BrainError(f"state must be a string, got {type(state).__name__}")
    return {"vel_r": vel_r, "vel_l": vel_l, "estimate": est,
            "state": None if state is None else state[:STATE_CHARS],
            "debug": clean_debug(get("debug"), signals, n_ir, plan)}


def _speed(key: str, val: Any) -> float:
    """A wheel speed that is not a finite float: a finite int becomes a float; anything else is refused."""
    if not real(val):
        raise BrainError(f"{key} must be a finite number (rad/s), got {val!r:.60}")
    return float(val)
