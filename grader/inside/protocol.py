"""Framing of the grader <-> worker messages: one JSON object per line, on a private pipe pair, and, for a
scenario's steps only, binary records (grader.inside.step_record) framed by HEADER.

Both directions use the same framing. The grader side is strict because the worker is untrusted after
student code has run: a message larger than the cap, a NaN/Infinity token, a duplicate key, or anything
but JSON types is a protocol violation. Non-finite floats that the student really returned are encoded
explicitly as {"$float": "nan" | "inf" | "-inf"} and decoded back into floats, so the checks can say
"returned NaN" instead of "broke the protocol".
"""

from __future__ import annotations

import json
import math
import re
import struct
from typing import Any, NamedTuple

from grader.inside.answer_bounds import too_large
from grader.inside.caps import clean

MAX_MESSAGE = 4 * 1024 * 1024  # bytes per message (a 30 s scenario step command is ~200 bytes)
_FLOAT_TAG = "$float"
_NONFINITE = {"nan": math.nan, "inf": math.inf, "-inf": -math.inf}
_SURROGATE_ESCAPE = re.compile(rb"\\u[dD][89a-fA-F]")
# A binary record's frame (grader.inside.step_record): kind byte, request id, payload bytes. The kind bytes
# are control characters, which no JSON line begins with.
HEADER = struct.Struct("<BII")
REQUEST = 1  # a scenario step's readings (grader -> worker)
ANSWER = 2   # the brain's answer to them (worker -> grader)
_KINDS = (REQUEST, ANSWER)


class ProtocolError(Exception):
    """A message that is not a well-formed, size-capped, JSON-only object."""


# built once: json.dumps with options builds a new encoder for every message
_WRITER = json.JSONEncoder(allow_nan=False, separators=(",", ":"))


def encode(message: dict) -> bytes:
    """One message as a line of JSON (the grader only sends JSON it built; `allow_nan=False` keeps it so)."""
    return _WRITER.encode(message).encode() + b"\n"


def encode_request(message: dict) -> bytes:
    """A grader's request as a line of JSON. What the grader builds is almost always plain JSON already
    (floats, lists, tuples, dicts), which json writes directly; a non-finite float, a numpy number or
    anything else json refuses takes the long way through `to_json` (the tagged form, or NotJSON)."""
    try:
        return _WRITER.encode(message).encode() + b"\n"
    except (ValueError, TypeError):
        return encode(to_json(message))


def decode_request(line: bytes) -> dict:
    """Parse one of the grader's requests (inside the worker). The grader is trusted and wrote it with
    `encode_request`, so plain json reads it; only a tagged non-finite float needs the strict decoder."""
    if b'"$float"' in line:
        return decode(line)
    try:
        value = json.loads(line)
    except (ValueError, RecursionError) as exc:  # UnicodeDecodeError is a ValueError
        raise ProtocolError(f"malformed message: {type(exc).__name__}") from None
    if not isinstance(value, dict):
        raise ProtocolError("message is not a JSON object")
    return value


def _reject_constant(token: str) -> Any:
    raise ProtocolError(f"non-JSON number {token!r} in message")


def _no_duplicates(pairs: list[tuple[str, Any]]) -> dict:
    out: dict = {}
    for key, value in pairs:
        if key in out:
            raise ProtocolError(f"duplicate key {key!r} in message")
        out[key] = value
    if len(out) == 1 and _FLOAT_TAG in out:
        tag = out[_FLOAT_TAG]
        if tag not in _NONFINITE:
            raise ProtocolError(f"bad {_FLOAT_TAG} value {tag!r}")
        return _NONFINITE[tag]  # type: ignore[return-value]
    return out


# built once: json.loads with hooks builds a new decoder (and its scanner) for every message
_STRICT = json.JSONDecoder(parse_constant=_reject_constant, object_pairs_hook=_no_duplicates)


def decode(line: bytes) -> dict:
    """Parse one message strictly; raises ProtocolError on anything but a JSON object."""
    if len(line) > MAX_MESSAGE:
        raise ProtocolError(f"message of {len(line)} bytes exceeds the {MAX_MESSAGE} byte cap")
    try:
        value = _STRICT.decode(line.decode("utf-8"))
    except ProtocolError:
        raise
    except (ValueError, RecursionError, UnicodeDecodeError) as exc:
        raise ProtocolError(f"malformed message: {type(exc).__name__}: {str(exc)[:200]}") from None
    if not isinstance(value, dict):
        raise ProtocolError("message is not a JSON object")
    # JSON may spell a lone surrogate ("\\ud800"); no such string may reach a UTF-8 writer later
    return clean(value) if _SURROGATE_ESCAPE.search(line) else value


class Record(NamedTuple):
    """A binary record (grader.inside.step_record) as framed on the pipe: its kind, request id, payload."""

    kind: int
    rid: int
    payload: bytes


class FrameReader:
    """Accumulates bytes from a pipe and yields whole frames: JSON lines, and binary records (a HEADER of
    kind REQUEST or ANSWER, which no JSON line starts with, then its payload). A line or record above
    the cap is refused as soon as its size is known, before it is buffered whole."""

    def __init__(self, cap: int = MAX_MESSAGE) -> None:
        self.cap = cap
        self._buf = bytearray()

    def feed(self, data: bytes) -> None:
        buf = self._buf
        buf += data
        if buf and buf[0] in _KINDS:
            if len(buf) >= HEADER.size and HEADER.unpack_from(buf)[2] > self.cap:
                raise ProtocolError(f"a record of {HEADER.unpack_from(buf)[2]} bytes exceeds the "
                                    f"{self.cap} byte cap")
        elif len(buf) > self.cap and b"\n" not in buf[: self.cap + 1]:
            raise ProtocolError(f"message exceeds the {self.cap} byte cap")

    def pop(self) -> bytes | Record | None:
        """The next whole frame: a line (bytes, without its newline) or a Record; None if none is whole
        yet. What follows a frame is checked against the cap too (`feed`'s rule)."""
        buf = self._buf
        if not buf:
            return None
        if buf[0] in _KINDS:
            if len(buf) < HEADER.size:
                return None
            kind, rid, size = HEADER.unpack_from(buf)
            if size > self.cap:
                raise ProtocolError(f"a record of {size} bytes exceeds the {self.cap} byte cap")
            end = HEADER.size + size
            if len(buf) < end:
                return None
            frame = Record(kind, rid, bytes(buf[HEADER.size:end]))
        else:
            end = buf.find(b"\n")
            if end < 0:
                return None
            frame = bytes(buf[:end])  # type: ignore[assignment]
            end += 1
        del buf[:end]
        if buf:
            self.feed(b"")
        return frame

    @property
    def pending(self) -> int:
        return len(self._buf)


_FLOATS = {float}


class NotJSON(TypeError):
    """A value the student returned that has no JSON form (an object, a set, a huge int...)."""


def to_json(value: Any, *, depth: int = 0) -> Any:
    """Convert what student code returned into plain JSON types (runs inside the worker).

    Only exact built-in types and numpy scalars/arrays are converted; any other object (for example one
    overriding __eq__ or __float__) is refused by name, so its methods are never trusted.
    """
    if depth > 32:
        raise NotJSON("a value nested more than 32 levels deep")
    kind = type(value)
    if kind is float:  # the commonest by far: wheel speeds, poses, readings
        return value if math.isfinite(value) else {_FLOAT_TAG: _nonfinite_name(value)}
    if kind is list or kind is tuple:
        if depth < 32 and value and set(map(type, value)) == _FLOATS:  # a row of floats (a command):
            total = sum(value)                          # one finiteness test for all (an overflowing sum
            if total - total == 0.0:                    # of finite ones takes the long way below)
                return list(value)
        return [to_json(v, depth=depth + 1) for v in value]
    if value is None or kind is bool or kind is str:
        return value
    if kind is int:
        if too_large(value):  # what a float holds, as the grader's side checks (answer_bounds)
            raise NotJSON("an integer too large to be a number of this course (no float holds it)")
        return value
    if kind is dict:
        out = {}
        for key, item in value.items():
            if type(key) is not str:
                raise NotJSON(f"a dict with a {type(key).__name__} key")
            out[key] = to_json(item, depth=depth + 1)
        return out
    converted = _numpy_to_python(value)
    if converted is not _NO:
        return to_json(converted, depth=depth + 1)
    raise NotJSON(f"a {kind.__name__} object")


def _nonfinite_name(x: float) -> str:
    return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")


_NO = object()


def _numpy_to_python(value: Any) -> Any:
    """numpy.float64 & co. and ndarrays become Python numbers and lists; anything else is _NO."""
    kind = type(value)
    if getattr(kind, "__module__", None) != "numpy":
        return _NO  # subclasses defined by student code live in their own module
    import numpy

    if isinstance(value, numpy.ndarray):
        if value.dtype.kind not in "biuf":
            return _NO
        return value.tolist()
    if isinstance(value, (numpy.floating, numpy.integer, numpy.bool_)):
        return value.item()
    return _NO
