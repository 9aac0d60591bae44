"""A scenario step as two fixed binary records: the readings (grader -> worker) and the brain's answer
(worker -> grader), laid out from the week's declared debug signals and IR count (`StepLayout`).

Both sides build the same layout: the grader sends its signal names and IR count in `brain_start`, and the
worker uses records only when they are its brain's own (else every step stays JSON). A record is framed by
grader.inside.protocol (kind, request id, payload length); its payload is one `struct` of fixed size,
then the UTF-8 bytes of the strings whose lengths that struct holds:

- readings: t, dt (double), ticks (2 int64), ir_raw (n_ir int64);
- answer: vel_r, vel_l, estimate x, y, theta (double), the state's byte length (uint16), one presence
  byte per signal in the declared order (0: None, 1: a value), then the values grouped by kind, each
  group in the declared order: the doubles of the scalars, the vector2s (two each) and the points (2 x
  columns each), the counts (int64), one byte per flag (0 or 1), the labels' byte lengths (uint16);
  then the state's and the labels' bytes. An absent signal's slot holds zeros.

An answer whose values are not already of their canonical type (a numpy float, an int speed, NaN in a
string's place, a string longer than its cap, anything else) is not a record: the worker sends it as JSON,
exactly as every answer was sent before records. The grader decodes a record into the same dict the JSON
would give and passes it to the same validation (simiam.brain.validate_command). It is the untrusted side's
output, so `decode_answer` checks the frame first: its size against the layout (to the byte, once the
declared string lengths are known, each within its cap), every presence and flag byte, strict UTF-8;
only then is a value taken from it. Nothing here is ever unpickled or evaluated.
"""

from __future__ import annotations

import struct
from collections.abc import Callable, Sequence
from typing import Any

from grader.inside.protocol import HEADER, REQUEST, ProtocolError
from grader.inside.record_codec import compile_codec
from grader.inside.record_writer import compile_writer
from simiam.signals import KINDS, LABEL_CHARS, MAX_COUNT, declared

STATE_CHARS = 80  # simiam.brain.STATE_CHARS, the validation's cap of a state name (the worker has no
#                   simiam.brain: tests/sandbox/test_checked_answers.py checks the two agree)
STATE_BYTES = 4 * STATE_CHARS  # UTF-8 bytes of a state name in a record
LABEL_BYTES = 4 * LABEL_CHARS  # of a label signal; longer ones: JSON
MAX_INT64 = 2**63 - 1
_BITS = b"\x00\x01"  # what a presence or flag byte may be (bytes.translate deletes them: nothing may be left)
# what an absent signal's slot holds (its presence byte says it is absent), by kind, for n columns
_ZERO: dict[str, Callable[[int], Any]] = {
    "scalar": lambda n: 0.0, "vector2": lambda n: [0.0, 0.0], "points": lambda n: [[0.0] * n, [0.0] * n],
    "label": lambda n: "", "count": lambda n: 0, "flag": lambda n: False}


class StepLayout:
    """The two records of one run's steps, for the signals `names` and `n_ir` IR sensors."""

    def __init__(self, names: Sequence[str], n_ir: int) -> None:
        self.names = tuple(names)
        self.n_ir = int(n_ir)
        self.readings = struct.Struct(f"<2d2q{self.n_ir}q")
        self._request = struct.Struct(HEADER.format + self.readings.format.lstrip("<"))  # header and readings
        signals = declared(self.names)
        group = {kind: tuple(s for s in signals if s.kind == kind) for kind in KINDS}
        self._scalars = tuple(s.name for s in group["scalar"])
        self._vectors = tuple(s.name for s in group["vector2"])
        self._points = tuple((s.name, s.columns(self.n_ir)) for s in group["points"])
        self._counts = tuple(s.name for s in group["count"])
        self._flags = tuple(s.name for s in group["flag"])
        self._labels = tuple(s.name for s in group["label"])
        self._zero = {s.name: _ZERO[s.kind](s.columns(self.n_ir)) for s in signals}  # an absent value's slot
        n_floats = len(self._scalars) + 2 * len(self._vectors) + sum(2 * n for _, n in self._points)
        self.answer = struct.Struct(f"<5dH{len(signals)}s{n_floats}d{len(self._counts)}q{len(self._flags)}s"
                                    f"{len(self._labels)}H")
        # where each group lands in the unpacked tuple: 0-5 the command, 6 the presence bytes, then the floats
        self._floats = 7
        self._vectors_at = 7 + len(self._scalars)
        self._vector_at = tuple((name, self._vectors_at + 2 * i) for i, name in enumerate(self._vectors))
        points_at, at = [], self._vectors_at + 2 * len(self._vectors)
        for name, n in self._points:
            points_at.append((name, at, n))
            at += 2 * n
        self._points_at = tuple(points_at)
        self._counts_at = 7 + n_floats
        self._flags_at = self._counts_at + len(self._counts)
        self._labels_at = self._flags_at + 1
        self._label_presence = tuple(self.names.index(name) for name in self._labels)
        self._all_present = b"\x01" * len(signals)
        self.max_answer = self.answer.size + STATE_BYTES + LABEL_BYTES * len(self._labels)
        self._caps = {"STATE_BYTES": STATE_BYTES, "LABEL_BYTES": LABEL_BYTES, "MAX_INT64": MAX_INT64,
                      "BITS": _BITS, "STATE_CHARS": STATE_CHARS, "LABEL_CHARS": LABEL_CHARS,
                      "MAX_COUNT": MAX_COUNT, "OF": (signals, self.n_ir)}
        self._encode, self._decode, self._decode_frame = compile_codec(self, self._caps)  # straight-line code

    def to_json(self) -> dict:
        """What brain_start sends: enough for the worker to build the same layout."""
        return {"signals": list(self.names), "n_ir": self.n_ir}

    # ---- readings: the grader writes them (trusted), the worker reads them ---------------------------
    def encode_readings(self, rid: int, readings: Any) -> bytes | None:
        """One step's readings as a record, or None where they do not fit the layout (then JSON)."""
        t, dt = readings["t"], readings["dt"]
        if type(t) is not float or type(dt) is not float:
            return None
        try:
            return self._request.pack(REQUEST, rid, self.readings.size, t, dt, *readings["ticks"],
                                      *readings["ir_raw"])
        except (struct.error, TypeError):
            return None

    def decode_readings(self, payload: bytes) -> dict:
        """The readings dict JSON would give, from a readings record's payload (inside the worker)."""
        if len(payload) != self.readings.size:
            raise ProtocolError(f"a readings record of {len(payload)} bytes, not {self.readings.size}")
        t, dt, right, left, *ir_raw = self.readings.unpack(payload)
        return {"t": t, "dt": dt, "ticks": [right, left], "ir_raw": ir_raw}

    def decode_request(self, data: bytes) -> tuple[int, dict] | None:
        """(request id, `decode_readings` of the payload) when `data` is exactly one whole readings record
        of this layout (its header read in the same unpacking: a step's common case); None otherwise,
        and the worker then reads `data` frame by frame."""
        if len(data) != self._request.size:
            return None
        kind, rid, size, t, dt, right, left, *ir_raw = self._request.unpack(data)
        if kind != REQUEST or size != self.readings.size:
            return None
        return rid, {"t": t, "dt": dt, "ticks": [right, left], "ir_raw": ir_raw}

    # ---- answers: the worker writes them, the grader checks and reads them ---------------------------
    def encode_answer(self, rid: int, answer: Any) -> bytes | None:
        """The brain's answer as a record, or None if any value is not of its canonical type (the worker
        then sends JSON, as before records)."""
        return self._encode(rid, answer)

    def writer(self, brain: Any) -> Callable[[int], bytes | dict]:
        """For `brain` (a LocalBrain of this layout's signals and IR count), after its `think`: `write(rid)`
        gives `encode_answer(rid, brain.answer())`, or `brain.answer()` where that is None, reading each
        value once (grader.inside.record_writer)."""
        return compile_writer(self, self._caps, brain)

    def decode_answer(self, payload: bytes) -> dict:
        """The answer dict JSON would give, from a record of the (untrusted) worker; ProtocolError for any
        frame that is not exactly of this layout. Every check on the frame comes before any value is
        taken from it."""
        return self._decode(payload)

    def decode_frame(self, data: bytes, rid: int, checked: type[dict] | None = None) -> dict | None:
        """`decode_answer` of the record `data` holds, when `data` is exactly one whole answer record of the
        request `rid` (its header read in the same unpacking as the fixed part: the step's common case);
        None when it is anything else (part of a record, more than one, JSON, another id, shorter than the
        fixed part), which the caller then reads frame by frame. The same checks in the same order and the
        same ProtocolError as `decode_answer` for a whole record that is not exactly of this layout.

        `checked` (the grading process passes simiam.brain.Checked): an answer whose every value is already
        what the command's validation would make of it (finite doubles, every row of a points signal of a
        finite sum, a state and labels within their character caps, counts from 0 to MAX_COUNT) comes as a
        `checked` of the same items, its `of` this layout's (signals, IR count), which the validation then
        takes as it is; any other answer comes as the plain dict, for the validation to check."""
        return self._decode_frame(data, rid, checked)


_LAYOUTS: dict[tuple, StepLayout] = {}


def layout_for(names: Sequence[str], n_ir: int) -> StepLayout:
    """The layout of `names` and `n_ir`, built once per process and kept (a handful per course)."""
    key = (tuple(names), int(n_ir))
    layout = _LAYOUTS.get(key)
    if layout is None:
        layout = _LAYOUTS[key] = StepLayout(*key)
    return layout
