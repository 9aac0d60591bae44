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
from itertools import chain
from operator import itemgetter
from typing import Any

from grader.inside.protocol import ANSWER, HEADER, REQUEST, ProtocolError
from simiam.signals import KINDS, declared

STATE_BYTES = 320  # UTF-8 bytes of a state name in a record (4 per character of simiam.brain.STATE_CHARS)
LABEL_BYTES = 320  # of a label signal (4 per character of simiam.signals.LABEL_CHARS); longer ones: JSON
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
        signals = declared(self.names)
        group = {kind: tuple(s for s in signals if s.kind == kind) for kind in KINDS}
        self._scalars = tuple(s.name for s in group["scalar"])
        self._vectors = tuple(s.name for s in group["vector2"])
        self._points = tuple((s.name, s.columns(self.n_ir)) for s in group["points"])
        self._counts = tuple(s.name for s in group["count"])
        self._flags = tuple(s.name for s in group["flag"])
        self._labels = tuple(s.name for s in group["label"])
        self._zero = {s.name: _ZERO[s.kind](s.columns(self.n_ir)) for s in signals}  # an absent value's slot
        self._get = {kind: _getter(tuple(s.name for s in group[kind])) for kind in KINDS}
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
            payload = self.readings.pack(t, dt, *readings["ticks"], *readings["ir_raw"])
        except (struct.error, TypeError):
            return None
        return HEADER.pack(REQUEST, rid, len(payload)) + payload

    def decode_readings(self, payload: bytes) -> dict:
        """The readings dict JSON would give (inside the worker)."""
        if len(payload) != self.readings.size:
            raise ProtocolError(f"a readings record of {len(payload)} bytes, not {self.readings.size}")
        t, dt, right, left, *ir_raw = self.readings.unpack(payload)
        return {"t": t, "dt": dt, "ticks": [right, left], "ir_raw": ir_raw}

    # ---- answers: the worker writes them, the grader checks and reads them ---------------------------
    def encode_answer(self, rid: int, answer: Any) -> bytes | None:
        """The brain's answer as a record, or None if any value is not of its canonical type (the worker
        then sends JSON, as before records)."""
        if type(answer) is not dict:
            return None
        get = answer.get
        vel_r, vel_l, est, state, debug = get("vel_r"), get("vel_l"), get("estimate"), get("state"), \
            get("debug")
        if type(vel_r) is not float or type(vel_l) is not float or type(est) is not list or len(est) != 3 \
                or type(state) is not str or type(debug) is not dict or len(debug) != len(self.names):
            return None
        x, y, theta = est
        if type(x) is not float or type(y) is not float or type(theta) is not float:
            return None
        presence = self._all_present
        if None in debug.values():  # absent signals: zeros in their slots, 0 in their presence bytes
            presence = bytes(debug.get(name, 0) is not None for name in self.names)
            debug = {name: self._zero[name] if value is None else value for name, value in debug.items()}
        try:
            fields = self._debug_fields(debug)
            texts = [state.encode(), *(text.encode() for text in fields.pop())]
        except (KeyError, TypeError, ValueError, AttributeError):  # UnicodeEncodeError: a lone surrogate
            return None
        if len(texts[0]) > STATE_BYTES or max(map(len, texts[1:]), default=0) > LABEL_BYTES:
            return None
        payload = self.answer.pack(vel_r, vel_l, x, y, theta, len(texts[0]), presence, *fields,
                                   *map(len, texts[1:])) + b"".join(texts)
        return HEADER.pack(ANSWER, rid, len(payload)) + payload

    def _debug_fields(self, debug: dict) -> list:
        """The debug values in the record's order (the floats, the counts, the flags' bytes) and, last,
        the labels; TypeError or ValueError for a value not of its kind's canonical type. Groups the
        layout does not have cost nothing."""
        get = self._get
        floats = list(get["scalar"](debug)) if self._scalars else []
        if self._vectors:
            vectors = get["vector2"](debug)
            if set(map(type, vectors)) != {list} or set(map(len, vectors)) != {2}:
                raise TypeError
            floats += chain.from_iterable(vectors)
        if self._points:
            for rows, (_name, n) in zip(get["points"](debug), self._points, strict=False):
                if type(rows) is not list or len(rows) != 2 or type(rows[0]) is not list \
                        or type(rows[1]) is not list or len(rows[0]) != n or len(rows[1]) != n:
                    raise TypeError
                floats += rows[0]
                floats += rows[1]
        if floats and set(map(type, floats)) != {float}:
            raise TypeError
        if self._counts:
            counts = get["count"](debug)
            if set(map(type, counts)) != {int} or not -MAX_INT64 <= min(counts) <= max(counts) <= MAX_INT64:
                raise ValueError
            floats += counts
        flags = get["flag"](debug) if self._flags else ()
        if flags and set(map(type, flags)) != {bool}:
            raise TypeError
        floats.append(bytes(flags))
        labels = get["label"](debug) if self._labels else ()
        if labels and set(map(type, labels)) != {str}:
            raise TypeError
        floats.append(labels)
        return floats

    def decode_answer(self, payload: bytes) -> dict:
        """The answer dict JSON would give, from a record of the (untrusted) worker; ProtocolError for any
        frame that is not exactly of this layout. Every check on the frame comes before any value is
        taken from it."""
        size, fixed = len(payload), self.answer.size
        if not fixed <= size <= self.max_answer:
            raise ProtocolError(f"a step record of {size} bytes, where this run's layout takes "
                                f"{fixed} to {self.max_answer}")
        raw = self.answer.unpack_from(payload)
        state_len, presence = raw[5], raw[6]
        if presence.translate(None, _BITS) or self._flags and raw[self._flags_at].translate(None, _BITS):
            raise ProtocolError("a presence or flag byte other than 0 or 1 in a step record")
        if state_len > STATE_BYTES:
            raise ProtocolError("a string in a step record longer than its cap")
        taken = fixed + state_len
        if self._labels:
            lengths = raw[self._labels_at:]
            if max(lengths) > LABEL_BYTES:
                raise ProtocolError("a string in a step record longer than its cap")
            for length, at in zip(lengths, self._label_presence, strict=False):
                if length and not presence[at]:
                    raise ProtocolError("a length for an absent label in a step record")
            taken += sum(lengths)
        if taken != size:
            raise ProtocolError(f"a step record of {size} bytes whose fields take {taken}")
        # the frame is whole and well-formed: now its values
        try:
            state = str(payload[fixed:fixed + state_len], "utf-8")
            debug: dict[str, Any] = dict(zip(self._scalars, raw[self._floats:self._vectors_at], strict=False))
            for name, at in self._vector_at:
                debug[name] = [raw[at], raw[at + 1]]
            for name, at, n in self._points_at:
                debug[name] = [list(raw[at:at + n]), list(raw[at + n:at + 2 * n])]
            if self._counts:
                debug.update(zip(self._counts, raw[self._counts_at:self._flags_at], strict=False))
            if self._flags:
                debug.update(zip(self._flags, map(bool, raw[self._flags_at]), strict=False))
            if self._labels:
                end = fixed + state_len
                for name, length in zip(self._labels, raw[self._labels_at:], strict=False):
                    debug[name] = str(payload[end:end + length], "utf-8")
                    end += length
        except UnicodeDecodeError:
            raise ProtocolError("a string in a step record that is not UTF-8") from None
        if presence != self._all_present:
            for name, present in zip(self.names, presence, strict=False):
                if not present:
                    debug[name] = None
        return {"vel_r": raw[0], "vel_l": raw[1], "estimate": [raw[2], raw[3], raw[4]], "state": state,
                "debug": debug}


def _getter(names: tuple[str, ...]) -> Callable[[dict], tuple]:
    """A function giving the values of `names` from a dict, as a tuple (KeyError for a missing one)."""
    if not names:
        return lambda _debug: ()
    if len(names) == 1:
        name = names[0]
        return lambda debug: (debug[name],)
    return itemgetter(*names)


_LAYOUTS: dict[tuple, StepLayout] = {}


def layout_for(names: Sequence[str], n_ir: int) -> StepLayout:
    """The layout of `names` and `n_ir`, built once per process and kept (a handful per course)."""
    key = (tuple(names), int(n_ir))
    layout = _LAYOUTS.get(key)
    if layout is None:
        layout = _LAYOUTS[key] = StepLayout(*key)
    return layout
