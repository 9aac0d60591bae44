"""The framing and value rules of the worker protocol, each shown against a naive version it improves on."""

from __future__ import annotations

import math

import numpy
import pytest
from sandbox_wrong import naive

from grader.inside import protocol
from grader.inside.protocol import FrameReader, NotJSON, ProtocolError, decode, encode, to_json

HOSTILE_LINES = [
    b'{"id": 1, "ok": true, "value": NaN}',
    b'{"id": 1, "ok": true, "value": -Infinity}',
    b'{"id": 1, "id": 2, "ok": true}',
    b'[1, 2, 3]',
    b'{"id": 1, "value": {"$float": "3.0"}}',
    b'{"id": 1, "value": "\xff"}',
    b"[" * 100_000 + b"]" * 100_000,
]


@pytest.mark.parametrize("line", HOSTILE_LINES)
def test_strict_decoder_refuses_what_json_loads_would_take(line):
    with pytest.raises(ProtocolError):
        decode(line)


def test_the_naive_decoder_lets_them_through():
    accepted = 0
    for line in HOSTILE_LINES:
        try:
            naive.decode(line)
            accepted += 1
        except (ValueError, RecursionError):
            pass
    assert accepted >= 4


def test_oversized_messages_are_refused_before_parsing():
    with pytest.raises(ProtocolError, match="cap"):
        decode(b'"' + b"x" * (protocol.MAX_MESSAGE + 1) + b'"')
    reader = FrameReader(cap=1000)
    with pytest.raises(ProtocolError, match="cap"):
        reader.feed(b"x" * 1001)


def test_line_reader_splits_and_keeps_partial_lines():
    reader = FrameReader()
    reader.feed(b'{"id": 1}\n{"id"')
    assert reader.pop() == b'{"id": 1}' and reader.pop() is None
    reader.feed(b': 2}\n')
    assert decode(reader.pop()) == {"id": 2}


def test_nonfinite_floats_cross_only_in_explicit_form():
    line = encode({"id": 1, "value": to_json([math.nan, math.inf, -math.inf, 1.5])}).rstrip(b"\n")
    assert b"NaN" not in line and b"Infinity" not in line
    value = decode(line)["value"]
    assert math.isnan(value[0]) and value[1:] == [math.inf, -math.inf, 1.5]


class Liar:
    def __eq__(self, other):
        return True

    def __float__(self):
        return 3.84


class LyingFloat(float):
    def __eq__(self, other):
        return True


@pytest.mark.parametrize("value, name", [(Liar(), "Liar"), (LyingFloat(1.0), "LyingFloat"),
                                         ({1: 2}, "int key"), ({1, 2}, "set"), (10**400, "too large")])
def test_to_json_refuses_objects_by_name(value, name):
    with pytest.raises(NotJSON, match=name):
        to_json(value)


def test_the_naive_converter_lets_a_liar_cross_as_a_number():
    assert naive.to_json([Liar()]) == [3.84]


def test_numpy_values_become_plain_numbers():
    value = to_json({"a": numpy.float64(1.5), "b": numpy.arange(3), "c": (numpy.int32(2), numpy.bool_(True))})
    assert value == {"a": 1.5, "b": [0, 1, 2], "c": [2, True]}
    assert type(value["a"]) is float and type(value["c"][1]) is bool


def test_deep_nesting_is_refused():
    deep: list = []
    for _ in range(40):
        deep = [deep]
    with pytest.raises(NotJSON, match="nested"):
        to_json(deep)


def test_requests_go_the_short_way_and_still_carry_what_json_cannot():
    """The grader's requests skip the to_json walk when json can write them as they are; a non-finite
    float or a numpy number takes the long way, and the worker reads both back."""
    from grader.inside.protocol import decode_request, encode_request

    plain = {"id": 1, "op": "brain_step", "readings": {"t": 0.5, "ticks": (1, 2), "ir_raw": [200] * 5}}
    assert encode_request(plain) == encode(to_json(plain))
    assert decode_request(encode_request(plain).rstrip(b"\n"))["readings"]["ticks"] == [1, 2]
    odd = {"id": 2, "op": "probe", "args": {"x": math.nan, "y": -math.inf, "z": numpy.float32(0.5),
                                            "n": numpy.int64(3)}}
    args = decode_request(encode_request(odd).rstrip(b"\n"))["args"]
    assert math.isnan(args["x"]) and args["y"] == -math.inf and args["z"] == 0.5 and args["n"] == 3
    with pytest.raises(NotJSON):
        encode_request({"id": 3, "op": "probe", "args": {"x": object()}})
    with pytest.raises(ProtocolError):
        decode_request(b"[1, 2]")
    with pytest.raises(ProtocolError):
        decode_request(b'{"id": 1, "op": ')
