"""Issue 24's faster step gives the numbers the step gave before, bit for bit: the command validation
(tests/data/before_issue24/validate.py keeps the version before), the speed limits (min/max before) and
the encoders (the formula before), for hostile inputs too. A points rule that hands back the brain's own
lists is caught (tests/data/wrong_physics/points_shared.py)."""

from __future__ import annotations

import importlib.util
import itertools
import math
import random
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from sim_helpers import wrong

from simiam.brain import BrainError, validate_command
from simiam.robot.quickbot import limit_speeds
from simiam.robot.rounding import round_half_away
from simiam.robot.wheel_encoder import WheelEncoder
from simiam.signals import SIGNALS, debug_plan, declared

_spec = importlib.util.spec_from_file_location(
    "before_issue24_validate", Path(__file__).parents[1] / "data" / "before_issue24" / "validate.py")
before = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(before)

EVERY_SIGNAL = declared(tuple(SIGNALS))
N_IR = 5


class Sub(float):
    """A float subclass: no kind accepts it (neither before nor now)."""


NUMBERS = [0.0, -0.0, 1.5, -2.25, 1e308, -1e308, math.inf, -math.inf, math.nan, 3, -7, 10**400, True, False,
           Sub(1.0), "1.5", None]
number = st.sampled_from(NUMBERS) | st.floats(allow_nan=True, allow_infinity=True) | st.integers()


def row(n: int):
    return st.lists(number, min_size=n, max_size=n)


value = st.recursive(
    number | st.text(max_size=100),
    lambda inner: st.lists(inner, max_size=6) | st.tuples(inner, inner)
    | st.lists(row(N_IR), min_size=2, max_size=2) | st.tuples(row(N_IR), row(N_IR)),
    max_leaves=14)
debug = st.dictionaries(st.sampled_from([*SIGNALS, "junk"]), value, max_size=len(SIGNALS))
command = st.fixed_dictionaries({}, optional={
    "vel_r": number, "vel_l": number, "estimate": value | st.lists(number, min_size=3, max_size=3),
    "state": st.none() | st.text(max_size=100) | number, "debug": debug | value})
good = st.fixed_dictionaries({
    "vel_r": st.floats(-10, 10), "vel_l": st.floats(-10, 10),
    "estimate": st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=3, max_size=3),
    "state": st.text(max_size=90),
    "debug": st.fixed_dictionaries({"ir_points_wf": st.lists(st.lists(st.floats(-1e308, 1e308), min_size=N_IR,
                                                                      max_size=N_IR), min_size=2, max_size=2),
                                    "u_ao": st.lists(st.floats(), min_size=2, max_size=2), "v": number})})


def lists_in(x, out=None) -> list:
    out = [] if out is None else out
    if isinstance(x, (list, dict)):
        out.append(x)
        for v in (x.values() if isinstance(x, dict) else x):
            lists_in(v, out)
    elif isinstance(x, tuple):
        for v in x:
            lists_in(v, out)
    return out


def same(a, b) -> bool:
    """Equal as the trace would hold them: the same types, floats to the bit (-0.0 and nan included)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, float):
        return a.hex() == b.hex() if a == a else b != b
    if isinstance(a, dict):
        return a.keys() == b.keys() and list(a) == list(b) and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    return a == b


def outcome(validate, cmd):
    try:
        return "ok", validate(cmd)
    except BrainError as exc:
        return "refused", str(exc)


def check(cmd) -> None:
    plan = debug_plan(EVERY_SIGNAL, N_IR)
    want = outcome(lambda c: before.validate_command(c, EVERY_SIGNAL, N_IR), cmd)
    got = outcome(lambda c: validate_command(c, EVERY_SIGNAL, N_IR, plan), cmd)
    assert got[0] == want[0] and same(got[1], want[1]), (cmd, got, want)
    if got[0] == "ok":  # a fresh command: nothing the brain holds and could change afterwards
        theirs = {id(x) for x in lists_in(cmd)}
        assert not any(id(x) in theirs for x in lists_in(got[1]))


@settings(max_examples=400, deadline=None)
@given(command | value)
def test_validation_is_the_same_for_anything_a_brain_answers(cmd):
    check(cmd)


@settings(max_examples=200, deadline=None)
@given(good)
def test_validation_is_the_same_for_well_formed_commands(cmd):
    check(cmd)


def test_a_points_rule_that_shares_the_brains_lists_is_caught(monkeypatch):
    wrong("points_shared").install(monkeypatch)
    cmds = [{"vel_r": 1.0, "vel_l": 1.0, "debug": {"ir_points_wf": [[0.1] * N_IR, [0.2] * N_IR]}},
            {"vel_r": 1.0, "vel_l": 1.0, "debug": {"ir_points_wf": [[Sub(0.1)] * N_IR, [0.2] * N_IR]}}]
    failures = 0
    for cmd in cmds:
        try:
            check(cmd)
        except AssertionError:
            failures += 1
    assert failures == len(cmds)


SPEEDS = [0.0, -0.0, 1.0, -1.0, 3.141592653589793, -3.141592653589793, 8.377580409572781, -8.377580409572781,
          13.613568165555769, 1e300, -1e-300, math.inf, -math.inf, math.nan, 5, -5]


def test_limits_are_min_then_max_as_before():
    for vel_r, vel_l in itertools.product(SPEEDS, repeat=2):
        for max_vel, min_vel in ((8.377580409572781, 0.0), (13.613568165555769, 3.141592653589793),
                                 (0.0, 0.0), (-1.0, 0.0)):
            r = max(min(vel_r, max_vel), -max_vel)
            ll = max(min(vel_l, max_vel), -max_vel)
            want = (0.0 if abs(r) < min_vel else r, 0.0 if abs(ll) < min_vel else ll)
            assert same(limit_speeds(vel_r, vel_l, max_vel, min_vel), want), (vel_r, vel_l, max_vel, min_vel)


@pytest.mark.parametrize("seed", range(5))
def test_encoders_count_as_before(seed):
    rng = random.Random(seed)
    encoder = WheelEncoder(16)
    ticks, residual = 0, 0.0
    for _ in range(3000):
        vel = rng.choice([rng.uniform(-14, 14), 0.0, -0.0, 8.377580409572781, math.pi / 0.033])
        dt = rng.choice([0.033, 0.05, 0.01])
        added = encoder.update(vel, dt)
        residual += vel * dt  # the formula before issue 24
        k = round_half_away(residual * 16 / (2 * math.pi))
        residual -= k * 2 * math.pi / 16
        ticks += k
        assert (added, encoder.ticks, encoder.residual.hex()) == (k, ticks, residual.hex())


@pytest.mark.parametrize("seed", range(3))
def test_the_move_is_diff_to_uni_and_the_chord_as_before(seed):
    from simiam.robot.dynamics import _sinc, diff_to_uni, move

    rng = random.Random(seed)
    R, L = 0.0325, 0.09925
    for _ in range(5000):
        x, y, theta = rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-50, 50)
        vel_r = rng.choice([rng.uniform(-14, 14), 0.0, -0.0, 8.377580409572781])
        vel_l = rng.choice([rng.uniform(-14, 14), vel_r, -vel_r, vel_r + 1e-9, vel_r * (1 + 1e-12)])
        dt = rng.choice([0.033, 0.05])
        v, w = diff_to_uni(R, L, vel_r, vel_l)  # move before issue 24
        if w == 0.0:
            want = (x + v * dt * math.cos(theta), y + v * dt * math.sin(theta), theta)
        else:
            half = w * dt / 2
            chord = v * dt * _sinc(half)
            want = (x + chord * math.cos(theta + half), y + chord * math.sin(theta + half), theta + w * dt)
        assert same(move(x, y, theta, vel_r, vel_l, R, L, dt), want)
