"""Issue 32: the grader's step decoder hands the validation an answer it has already validated
(simiam.brain.Checked) only when the validation would give every value back as it is: for any well-formed
answer record, a Checked one is exactly `validate_command` of the plain dict, values and types; honest
answers of every week's solution run all come out Checked (the cheap path is the one taken); and the
validation takes a Checked as it is only for its own signals and IR count.

The wrong version sandbox_wrong/lax_checked.py (no finiteness test) is caught by `_checked_differs`.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from sandbox_wrong.lax_checked import lax_layout

from grader.inside import step_record
from grader.inside.protocol import ANSWER, HEADER
from grader.inside.step_record import StepLayout
from simiam import brain
from simiam.brain import BrainError, Checked, validate_command
from simiam.control.local_brain import LocalBrain
from simiam.course.weeks import get_week
from simiam.signals import LABEL_CHARS, MAX_COUNT, declared, week_signals

REPO = Path(__file__).resolve().parents[2]
WEEKS = (3, 5, 6, 7)  # between them every kind of signal: scalars, vectors, points, a label, counts, flags
ODD = [float("nan"), float("inf"), -float("inf"), 1e308, -1e308, 0.0, -0.0, 5e-324]


def _layout(week: int) -> StepLayout:
    declaration = get_week(week)
    return StepLayout(week_signals(declaration), len(declaration.spec.ir_mounts))


def _frame(layout: StepLayout, doubles: list[float], counts: list[int], flags: list[int], presence: list[int],
           state: str, labels: list[str]) -> bytes:
    """A well-formed answer record of `layout` for request 9 (any values: the decoder reads them all)."""
    fixed = layout.answer
    text = state.encode()
    label_bytes = [t.encode() if presence[at] else b""  # an absent label's length must be 0
                   for t, at in zip(labels, layout._label_presence, strict=True)]  # noqa: SLF001
    payload = fixed.pack(*doubles[:5], len(text), bytes(presence), *doubles[5:], *counts, bytes(flags),
                         *(len(b) for b in label_bytes)) + text + b"".join(label_bytes)
    return HEADER.pack(ANSWER, 9, len(payload)) + payload


def _shape(layout: StepLayout) -> tuple[int, int, int, int]:
    """(doubles, counts, flags, labels) of the layout's fixed part."""
    raw = layout.answer.unpack(bytes(layout.answer.size))
    n_doubles = sum(1 for v in raw if type(v) is float)
    return n_doubles, len(layout._counts), len(layout._flags), len(layout._labels)  # noqa: SLF001


def _typed(value: object) -> object:
    """`value` with every leaf paired with its type: 1 == 1.0 == True must not hide a difference."""
    if isinstance(value, dict):
        return (type(value).__name__ if type(value) is not Checked else "dict",
                [(k, _typed(v)) for k, v in value.items()])
    if isinstance(value, list):
        return ("list", [_typed(v) for v in value])
    return (type(value).__name__, value)


def _checked_differs(layout: StepLayout, frame: bytes) -> str:
    """'' when the decoder's answer to `frame` is either plain, or Checked and exactly what the validation
    makes of the plain answer; else what differs."""
    plain = layout.decode_frame(frame, 9)
    got = layout.decode_frame(frame, 9, Checked)
    if type(plain) is not dict or repr(_typed(got)) != repr(_typed(plain)):  # repr: NaN is NaN here
        return f"the checked decoding {got!r} is not the plain one {plain!r}"
    if type(got) is not Checked:
        return ""
    signals = declared(layout.names)
    if got.of != (signals, layout.n_ir):
        return f"a Checked answer of {got.of!r}"
    try:
        validated = validate_command(dict(plain), signals, layout.n_ir)
    except BrainError as exc:
        return f"a Checked answer the validation refuses: {exc}"
    if repr(_typed(validated)) != repr(_typed(got)):
        return f"a Checked answer {got!r} the validation makes {validated!r}"
    return ""


@st.composite
def _frames(draw: st.DrawFn, layout: StepLayout) -> bytes:
    n_doubles, n_counts, n_flags, n_labels = _shape(layout)
    double = st.one_of(st.sampled_from(ODD), st.floats(allow_nan=True, allow_infinity=True),
                       st.floats(-10, 10))
    doubles = draw(st.lists(double, min_size=n_doubles, max_size=n_doubles))
    counts = draw(st.lists(st.one_of(st.integers(-2**63, 2**63 - 1), st.integers(-2, MAX_COUNT + 2)),
                           min_size=n_counts, max_size=n_counts))
    flags = draw(st.lists(st.integers(0, 1), min_size=n_flags, max_size=n_flags))
    presence = draw(st.lists(st.integers(0, 1), min_size=len(layout.names), max_size=len(layout.names)))
    text = st.text(max_size=LABEL_CHARS + 3)
    state = draw(st.one_of(text, st.text("ab", min_size=78, max_size=82), st.text("é€😀", max_size=81)))
    labels = draw(st.lists(st.one_of(text, st.text("é", min_size=LABEL_CHARS - 1, max_size=LABEL_CHARS + 1)),
                           min_size=n_labels, max_size=n_labels))
    return _frame(layout, doubles, counts, flags, presence, state, labels)


_LAYOUTS = {week: _layout(week) for week in WEEKS}


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data(), st.sampled_from(WEEKS))
def test_a_checked_answer_is_exactly_its_validated_command(data, week):
    layout = _LAYOUTS[week]
    assert _checked_differs(layout, data.draw(_frames(layout))) == ""


def _honest(layout: StepLayout, points: float = 0.5, speed: float = 1.5, state: str = "go_to_goal",
            count: int = 3) -> bytes:
    n_doubles, n_counts, n_flags, n_labels = _shape(layout)
    doubles = [speed, -2.25, 0.1, 0.2, -3.0] + [points] * (n_doubles - 5)
    return _frame(layout, doubles, [count] * n_counts, [1] * n_flags, [1] * len(layout.names), state,
                  ["left"] * n_labels)


@pytest.mark.parametrize("week", WEEKS)
def test_the_cases_at_each_rule_edge(week):
    """Each rule's edge, on both sides: Checked where the validation keeps the value, plain where not."""
    layout = _LAYOUTS[week]
    checked = [_honest(layout), _honest(layout, state="x" * 80), _honest(layout, state="é" * 40),
               _honest(layout, count=0), _honest(layout, count=MAX_COUNT), _honest(layout, points=1e300)]
    plain = [_honest(layout, speed=math.nan), _honest(layout, speed=math.inf),
             _honest(layout, state="x" * 81),
             _honest(layout, state="é" * 41)]  # 82 bytes: 41 characters, kept, but not taken as it is
    if layout._counts:  # noqa: SLF001
        plain += [_honest(layout, count=-1), _honest(layout, count=MAX_COUNT + 1)]
    if layout._points:  # noqa: SLF001 - five finite 1e308s: their sum is not finite, the points rule says None
        plain += [_honest(layout, points=1e308)]
    for frame in checked:
        assert type(layout.decode_frame(frame, 9, Checked)) is Checked, frame
        assert _checked_differs(layout, frame) == ""
    for frame in plain:
        assert type(layout.decode_frame(frame, 9, Checked)) is dict, frame
        assert _checked_differs(layout, frame) == ""


@pytest.mark.parametrize("week", [3, 6])
def test_the_test_catches_a_decoder_that_marks_without_the_finiteness_test(week):
    lax = lax_layout(week)
    found = [_checked_differs(lax, _honest(lax, speed=math.nan))]
    if lax._points:  # noqa: SLF001
        found.append(_checked_differs(lax, _honest(lax, points=1e308)))
    assert all(found), found


class _Recording(LocalBrain):
    """LocalBrain keeping its answers."""

    def __init__(self, *args: object) -> None:
        super().__init__(*args)  # type: ignore[arg-type]
        self.answers: list[dict] = []

    def step(self, readings):  # type: ignore[no-untyped-def]
        answer = super().step(readings)
        self.answers.append(answer)
        return answer


def test_honest_answers_of_every_solution_run_come_out_checked():
    """The cheap path is the one a run takes: every step of each week's `simiam run` scenario, run by the
    solution, decodes into a Checked answer that the validation returns as it is."""
    from simiam.course.loader import load_submission
    from simiam.simulator import Simulator
    from simiam.world import load_world

    for week_n in (3, 4, 5, 6, 7):
        week = get_week(week_n)
        layout = step_record.layout_for(week_signals(week), len(week.spec.ir_mounts))
        sub = load_submission(REPO / "solutions" / f"week{week_n}", week)
        signals, n_ir = declared(week_signals(week)), len(week.spec.ir_mounts)
        recording = _Recording(sub, week)
        world = load_world(week.world)
        sim = Simulator(world, recording, week.spec, dt=week.dt, start=world.start,
                        signals=week_signals(week))
        for _ in range(300):
            sim.step()
        sub.unload()
        for k, answer in enumerate(recording.answers):
            frame = layout.encode_answer(k, answer)
            assert frame is not None
            got = layout.decode_frame(frame, k, Checked)
            assert type(got) is Checked and validate_command(got, signals, n_ir) is got, (week_n, k)
            assert _typed(validate_command(dict(got), signals, n_ir)) == _typed(got)


def test_the_validation_takes_a_checked_answer_only_for_its_own_signals():
    week = get_week(6)
    signals, n_ir = declared(week_signals(week)), len(week.spec.ir_mounts)
    forged = Checked(vel_r=math.nan, vel_l=0.0, estimate=None, state="s", debug={})
    forged.of = (declared(week_signals(get_week(3))), n_ir)  # another week's signals
    with pytest.raises(BrainError, match="vel_r must be a finite number"):
        validate_command(forged, signals, n_ir)
    forged.of = (signals, n_ir + 1)  # another IR count
    with pytest.raises(BrainError, match="vel_r must be a finite number"):
        validate_command(forged, signals, n_ir)
    forged.of = (signals, n_ir)
    assert validate_command(forged, signals, n_ir) is forged  # trusted code's word: no brain makes one


def test_the_state_cap_is_the_validations():
    assert step_record.STATE_CHARS == brain.STATE_CHARS
    assert step_record.STATE_BYTES == 4 * brain.STATE_CHARS


@example(b"")  # the decoder's other answers stay as they were: None for what is not a whole record
@given(st.binary(max_size=300))
@settings(max_examples=100, deadline=None)
def test_what_is_not_a_whole_record_is_none_with_or_without_checked(data):
    layout = _LAYOUTS[6]
    try:
        plain = layout.decode_frame(data, 9)
    except Exception as exc:  # noqa: BLE001 - a ProtocolError: the same one either way
        with pytest.raises(type(exc)):
            layout.decode_frame(data, 9, Checked)
        return
    assert (plain is None) == (layout.decode_frame(data, 9, Checked) is None)

