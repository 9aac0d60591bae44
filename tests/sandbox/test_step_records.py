"""Issue 32: a scenario step's binary records (grader.inside.step_record). Honest answers decode into the
dict JSON gives; random and hostile frames, through the decoder and through a real worker, are protocol
violations with a clear message (or, well-formed, go to the same validation as JSON), never a crash of the
grader, and no value is taken from a frame before its size is checked against the layout.

The wrong version sandbox_wrong/trusting_records.py (values read before the frame's size is checked) is
caught by `_accepted_hostile`.
"""

from __future__ import annotations

import json
import math
import shutil
import struct
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sandbox_helpers import PROBES, attack
from sandbox_wrong.trusting_records import TrustingLayout

from grader.inside.protocol import ANSWER, HEADER, FrameReader, ProtocolError, decode, encode, to_json
from grader.inside.step_record import LABEL_BYTES, STATE_BYTES, StepLayout, layout_for
from grader.sandbox.errors import WorkerDied
from grader.sandbox.limits import Limits
from grader.sandbox.session import RemoteBrain, StudentSession
from simiam.brain import BrainError, validate_command
from simiam.course.weeks import get_week
from simiam.signals import SIGNALS, declared, week_signals

REPO = Path(__file__).resolve().parents[2]
FORGE = REPO / "tests" / "data" / "attacks" / "forge_records" / "forge.py"
READINGS = {"t": 0.033, "dt": 0.033, "ticks": [3, 2], "ir_raw": [200, 300, 917, 133, 450]}
SAMPLE = {"scalar": 0.25, "vector2": [0.5, -1.5], "label": "gauche é", "count": 3, "flag": True}


def _layout(week: int, cls: type[StepLayout] = StepLayout) -> StepLayout:
    declaration = get_week(week)
    return cls(week_signals(declaration), len(declaration.spec.ir_mounts))


def _answer(layout: StepLayout, absent: frozenset[str] = frozenset(), state: str = "go_to_goal") -> dict:
    debug = {}
    for name in layout.names:
        n = SIGNALS[name].columns(layout.n_ir)
        kind = SIGNALS[name].kind
        debug[name] = None if name in absent else \
            [[0.1 * i for i in range(n)], [-0.2 * i for i in range(n)]] if kind == "points" else SAMPLE[kind]
    return {"vel_r": 1.5, "vel_l": -2.25, "estimate": [0.1, 0.2, -3.0], "state": state, "debug": debug}


def _payload(layout: StepLayout, answer: dict) -> bytes:
    frame = layout.encode_answer(7, answer)
    assert frame is not None, f"an honest answer was not a record: {answer}"
    kind, rid, size = HEADER.unpack_from(frame)
    assert (kind, rid, size) == (ANSWER, 7, len(frame) - HEADER.size)
    return frame[HEADER.size:]


def _via_json(answer: dict) -> dict:
    return decode(encode({"id": 7, "ok": True, "value": to_json(answer)}))["value"]


@pytest.mark.parametrize("week", [3, 4, 5, 6, 7])
def test_an_honest_answer_decodes_into_what_json_gives(week):
    layout = _layout(week)
    for absent in (frozenset(), frozenset(layout.names[::2]), frozenset(layout.names)):
        answer = _answer(layout, absent)
        decoded = layout.decode_answer(_payload(layout, answer))
        assert decoded == _via_json(answer) == answer
        assert list(decoded["debug"]) == list(_via_json(answer)["debug"])  # the declared order, as JSON's
    frame = layout.encode_readings(3, READINGS)
    assert frame is not None and layout.decode_readings(frame[HEADER.size:]) == READINGS


def test_values_not_of_their_canonical_type_are_sent_as_json():
    """Where a record could not say exactly what JSON says, the worker sends JSON (encode_answer: None)."""
    import numpy

    layout = _layout(6)
    honest = _answer(layout)
    for change in ({"vel_r": 1}, {"vel_r": numpy.float64(1.0)}, {"estimate": [0.1, 0.2]}, {"state": None},
                   {"state": "x" * (STATE_BYTES + 1)}, {"state": "\ud800"},
                   {"debug": dict(honest["debug"], v=numpy.float64(0.5))},
                   {"debug": dict(honest["debug"], fw_direction="y" * (LABEL_BYTES + 1))},
                   {"debug": dict(honest["debug"], u_fw=[1.0, 2.0, 3.0])},
                   {"debug": dict(honest["debug"], extra=1.0)}):
        assert layout.encode_answer(1, {**honest, **change}) is None, change
    counts = _layout(5) if "switches" in week_signals(get_week(5)) else None
    if counts is not None:
        answer = _answer(counts)
        answer["debug"]["switches"] = 2**70  # beyond an int64: JSON, whose bounds say what it may be
        assert counts.encode_answer(1, answer) is None


def _hostile(layout: StepLayout) -> dict[str, bytes]:
    """Frames of the layout, each broken in one way (payloads, without the record's header)."""
    answer = _answer(layout)
    good = _payload(layout, answer)
    fixed = layout.answer.size
    state_len = struct.unpack_from("<H", good, 40)[0]
    presence = 42
    frames = {
        "empty": b"",
        "truncated by one": good[:-1],
        "truncated into the fixed part": good[:fixed - 3],
        "one byte more": good + b"\x00",
        "a state without its bytes": good[:fixed],
        "bad UTF-8 in the state": good[:fixed] + b"\xff" * state_len + good[fixed + state_len:],
        "a state's length beyond its cap": good[:40] + struct.pack("<H", STATE_BYTES + 1) + good[42:]
        + b"a" * (STATE_BYTES + 1 - state_len),
        "a state's length that overlaps a label": good[:40] + struct.pack("<H", state_len + 2) + good[42:],
        "a presence byte of 2": good[:presence] + b"\x02" + good[presence + 1:],
        "oversize": good + b"a" * (layout.max_answer + 1 - len(good)),
    }
    if layout._labels:
        at = fixed - 2 * len(layout._labels)
        frames["a label's length beyond the bytes sent"] = good[:at] + struct.pack("<H", 200) + good[at + 2:]
        absent = _payload(layout, _answer(layout, frozenset(layout._labels)))
        frames["a length for an absent label"] = absent[:at] + struct.pack("<H", 1) + absent[at + 2:] + b"a"
    if layout._flags:
        flags_at = fixed - 2 * len(layout._labels) - len(layout._flags)
        frames["a flag byte of 5"] = good[:flags_at] + b"\x05" + good[flags_at + 1:]
    return frames


def _accepted_hostile(layout: StepLayout) -> list[str]:
    """The hostile frames `layout` decodes instead of refusing, and any refused without a ProtocolError."""
    wrong = []
    for name, payload in _hostile(layout).items():
        try:
            layout.decode_answer(payload)
        except ProtocolError as exc:
            assert str(exc), name
            continue
        except Exception as exc:  # noqa: BLE001 - the grader's decoder crashed: that is what is looked for
            wrong.append(f"{name}: {type(exc).__name__}: {exc}")
            continue
        wrong.append(f"{name}: decoded")
    return wrong


@pytest.mark.parametrize("week", [3, 5, 6, 7])
def test_every_hostile_frame_is_a_protocol_violation(week):
    assert _accepted_hostile(_layout(week)) == []


def _framed_differs(layout: StepLayout, payload: bytes) -> str:
    """'' when decode_frame of `payload` framed as the answer to request 9 gives what decode_answer gives
    (the same dict or the same ProtocolError), or None for a payload shorter than the fixed part (the
    caller then reads it frame by frame, into decode_answer); and None for another id or kind."""
    frame = HEADER.pack(ANSWER, 9, len(payload)) + payload
    results = []
    for decode_one in (lambda: layout.decode_answer(payload), lambda: layout.decode_frame(frame, 9)):
        try:
            results.append(decode_one())
        except ProtocolError as exc:
            results.append(f"ProtocolError: {exc}")
    plain, framed = results
    wanted = None if len(payload) < layout.answer.size else plain
    if json.dumps(framed, sort_keys=True) != json.dumps(wanted, sort_keys=True):
        return f"framed {framed!r}, plain {plain!r}"
    for other in (HEADER.pack(ANSWER, 8, len(payload)) + payload, HEADER.pack(1, 9, len(payload)) + payload,
                  frame + b"x", frame[:-1]):
        if len(other) >= HEADER.size + layout.answer.size and layout.decode_frame(other, 9) is not None:
            return f"decoded another frame: {other!r}"
    return ""


@pytest.mark.parametrize("week", [3, 5, 6, 7])
def test_the_framed_decoder_gives_what_the_payload_decoder_gives(week):
    layout = _layout(week)
    frames = {**_hostile(layout), "honest": _payload(layout, _answer(layout)),
              "absent": _payload(layout, _answer(layout, frozenset(layout.names)))}
    assert {name: d for name, p in frames.items() if (d := _framed_differs(layout, p))} == {}


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from([3, 6, 7]), st.binary(max_size=400), st.integers(0, 3))
def test_the_framed_decoder_gives_what_the_payload_decoder_gives_for_random_bytes(week, noise, splice):
    layout = layout_for(week_signals(get_week(week)), 5)
    honest = _payload(layout, _answer(layout))
    payload = noise if splice == 0 else (honest[:len(honest) - len(noise)] + noise)[:len(honest)]
    assert _framed_differs(layout, payload) == ""


def test_the_test_catches_a_decoder_that_reads_before_it_checks():
    missed = _accepted_hostile(_layout(6, TrustingLayout))
    assert any("truncated by one: decoded" in m for m in missed), missed
    assert any("one byte more: decoded" in m for m in missed), missed


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from([3, 6, 7]), st.binary(max_size=400), st.integers(0, 3))
def test_random_bytes_are_refused_or_a_command_the_validation_judges(week, noise, splice):
    """Random payloads, and honest ones with random bytes written over them: a ProtocolError, or a dict of
    the canonical types, which the simulator's validation accepts or refuses as an invalid command."""
    layout = layout_for(week_signals(get_week(week)), 5)
    honest = _payload(layout, _answer(layout))
    payload = noise if splice == 0 else (honest[:len(honest) - len(noise)] + noise)[:len(honest)]
    try:
        value = layout.decode_answer(payload)
    except ProtocolError as exc:
        assert str(exc)
        return
    assert set(value) == {"vel_r", "vel_l", "estimate", "state", "debug"}
    assert set(value["debug"]) == set(layout.names)
    try:
        validate_command(value, declared(layout.names), layout.n_ir)
    except BrainError as exc:
        assert "finite" in str(exc)  # the only way a well-formed record is an invalid command


@settings(max_examples=200, deadline=None)
@given(st.lists(st.binary(max_size=64), max_size=8))
def test_the_frame_reader_refuses_or_splits_any_stream(chunks):
    reader = FrameReader(cap=256)
    try:
        for chunk in chunks:
            reader.feed(chunk)
            while (frame := reader.pop()) is not None:
                assert isinstance(frame, (bytes, tuple))
    except ProtocolError as exc:
        assert "cap" in str(exc)


def test_a_record_announcing_more_than_the_cap_is_refused_before_it_is_read():
    reader = FrameReader(cap=1000)
    with pytest.raises(ProtocolError, match="exceeds the 1000 byte cap"):
        reader.feed(HEADER.pack(ANSWER, 1, 1 << 30))


def test_nan_in_a_record_is_the_invalid_command_json_gives():
    layout = _layout(3)
    answer = {**_answer(layout), "vel_r": math.nan}
    for value in (layout.decode_answer(_payload(layout, answer)), _via_json(answer)):
        with pytest.raises(BrainError, match="vel_r must be a finite number"):
            validate_command(value, declared(layout.names), layout.n_ir)


# ---- through a real worker -------------------------------------------------------------------------------
FORGED = [  # (how the worker's record is changed, what the grader says)
    ("truncated", "broke the protocol .a step record of \\d+ bytes whose fields take"),
    ("longer", "broke the protocol .a step record of \\d+ bytes whose fields take"),
    ("oversize", "broke the protocol .a record of 1073741824 bytes exceeds"),
    ("bad_utf8", "broke the protocol .a string in a step record that is not UTF-8"),
    ("state_too_long", "broke the protocol .a step record of \\d+ bytes, where this run's layout takes"),
    ("presence_2", "broke the protocol .a presence or flag byte other than 0 or 1"),
    ("wrong_kind", "broke the protocol .a step record nobody asked for"),
    ("wrong_id", "an answer that does not match the question"),
    ("twice", "an answer that does not match the question"),
]


def _forging_week3(shared_dir: Path) -> Path:
    folder = shared_dir / "forge"
    shutil.copytree(REPO / "solutions" / "week3", folder)
    drive = folder / "differential_drive.py"
    drive.write_text(drive.read_text() + "\n\n" + FORGE.read_text())
    for p in (folder, *folder.iterdir()):
        p.chmod(0o755 if p.is_dir() else 0o644)
    return folder


def test_hostile_records_from_a_real_worker_are_protocol_violations(shared_dir, mode):
    with StudentSession(3, _forging_week3(shared_dir), Limits(call_seconds=5.0), sandbox=mode,
                        probes="sandbox_probes", extra_paths=(str(PROBES),)) as session:
        brain = RemoteBrain(session, {"goal": [0.5, 0.5]})
        honest = brain.step(READINGS)
        assert brain._layout is not None and validate_command(honest)["state"]  # records were agreed
        for how, words in FORGED:
            attack(session, fn="forge", how=how)
            brain = RemoteBrain(session, {"goal": [0.5, 0.5]})
            with pytest.raises(WorkerDied, match=words):
                brain.step(READINGS)
                brain.step(READINGS)  # "twice": the second answer is found at the next step
            assert session._worker is None or session._worker.dead, how
        attack(session, fn="forge", how="nan_speed")
        value = RemoteBrain(session, {"goal": [0.5, 0.5]}).step(READINGS)
        with pytest.raises(BrainError, match="vel_r must be a finite number"):
            validate_command(value)
        with pytest.raises(WorkerDied, match="a step record nobody asked for"):
            attack(session, fn="unasked")  # its own answer is already a record where JSON is due
        assert json.dumps(RemoteBrain(session, {"goal": [0.5, 0.5]}).step(READINGS))  # a fresh worker answers
