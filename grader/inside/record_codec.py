"""The answer record's codec, written out for one layout (grader.inside.step_record.StepLayout).

A scenario step costs its codec on both sides of the sandbox every step, and on one core shared by the two
processes every step runs cold (issue 32): the general codec's loops over signal kinds, getters and slices
were most of a week-3 step. So each layout gets its encoder and decoder as straight-line Python, generated
once from the layout (a handful per course) and compiled with `compile`: one statement per signal, no
loop, no lookup by name at run time. The generated source uses only the layout's positions and, as string
literals (`repr`), the names of the week's declared signals (simiam.signals: identifiers of the trusted
registry, never anything the worker sent). `source(layout)` shows it.

What they do is step_record's contract, unchanged: the encoder gives None (the worker then sends JSON) for
any value not of its canonical type; the decoder checks the whole frame (its size to the byte, every
presence and flag byte, each string's cap, strict UTF-8) before it takes any value, and builds the dict
JSON would give, keys in the declared order.
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from typing import Any

from grader.inside.protocol import ANSWER, HEADER, ProtocolError
from simiam.signals import MAX_POINTS, declared

Encoder = Callable[[int, Any], "bytes | None"]
Decoder = Callable[[bytes], dict]
FrameDecoder = Callable[[bytes, int, "type[dict] | None"], "dict | None"]


def source(layout: Any) -> str:
    """The Python source of `layout`'s encoder and decoders (functions `encode`, `decode` and
    `decode_frame`)."""
    return "\n\n".join((_encoder(layout), _decoder(layout, framed=False), _decoder(layout, framed=True)))


def compile_codec(layout: Any, caps: dict[str, Any]) -> tuple[Encoder, Decoder, FrameDecoder]:
    """`layout`'s encoder and decoders (see the module docstring); `caps`: the record's STATE_BYTES,
    LABEL_BYTES, MAX_INT64 and BITS (the bytes a presence or flag byte may be)."""
    space = namespace(layout, caps)
    exec(compile(source(layout), f"<step record codec {','.join(layout.names)} {layout.n_ir}>", "exec"),  # noqa: S102
         space)
    return space["encode"], space["decode"], space["decode_frame"]


def namespace(layout: Any, caps: dict[str, Any]) -> dict[str, Any]:
    """The names the generated code of `layout` reads (its structs, sizes and caps)."""
    framed = struct.Struct(HEADER.format + layout.answer.format.lstrip("<"))  # header and fixed part
    return {
        "ProtocolError": ProtocolError, "UnicodeDecodeError": UnicodeDecodeError,
        "PACK": framed.pack,  # one pack per answer
        "UNPACK": layout.answer.unpack_from, "ANSWER": ANSWER, "FIXED": layout.answer.size,
        "UNPACK_FRAME": framed.unpack_from, "HEAD": HEADER.size,
        "MAX": layout.max_answer, **caps, "ALL": layout._all_present,  # noqa: SLF001
        "FLOATS": {float}, "NAMES": layout.names,
        "ZERO": tuple(layout._zero[name] for name in layout.names),  # noqa: SLF001
    }


def _kinds(layout: Any) -> list[tuple[int, str, str, int]]:
    """(position in the declared order, name, kind, columns) of each signal."""
    return [(i, s.name, s.kind, s.columns(layout.n_ir)) for i, s in enumerate(declared(layout.names))]


def _encoder(layout: Any) -> str:
    n = len(layout.names)
    lines = [
        "def encode(rid, answer):",
        "    if type(answer) is not dict:",
        "        return None",
        "    get = answer.get",
        "    est, state, debug = get('estimate'), get('state'), get('debug')",
        "    if type(est) is not list or len(est) != 3 or type(state) is not str \\",
        f"            or type(debug) is not dict or len(debug) != {n}:",
        "        return None",
        "    vel_r, vel_l = get('vel_r'), get('vel_l')",
    ]
    if n:
        lines += ["    try:",
                  "        " + "; ".join(f"v{i} = debug[{name!r}]" for i, name in enumerate(layout.names)),
                  "    except KeyError:",
                  "        return None"]
    return "\n".join(lines + pack_lines(layout, "return None"))


def pack_lines(layout: Any, fail: str) -> list[str]:
    """The encoder's checks and packing (body lines of a function): from `vel_r`, `vel_l`, `est` (a list of
    three), `state` (a str) and `v0`, `v1`, ... (each signal's value or None, in the declared order), the
    record `PACK` gives; `fail` (a statement) wherever a value is not of its canonical type. The `v`s of
    absent signals are set to their slot's zeros on the way."""
    signals = _kinds(layout)
    lines = []
    if signals:
        lines += ["    presence = ALL",
                  "    if " + " or ".join(f"v{i} is None" for i, *_ in signals) + ":",
                  "        presence = bytes((" + "".join(f"v{i} is not None, " for i, *_ in signals) + "))"]
        lines += [f"        if v{i} is None:\n            v{i} = ZERO[{i}]" for i, *_ in signals]
    else:
        lines += ["    presence = ALL"]
    grouped: dict[str, list[str]] = {"scalar": [], "vector2": [], "points": []}
    counts, flags, labels = [], [], []
    for i, _name, kind, cols in signals:
        if kind == "scalar":
            grouped[kind].append(f"v{i}")
        elif kind == "vector2":
            lines += [f"    if type(v{i}) is not list or len(v{i}) != 2:", f"        {fail}"]
            grouped[kind].append(f"*v{i}")
        elif kind == "points":
            lines += [f"    if type(v{i}) is not list or len(v{i}) != 2:", f"        {fail}",
                      f"    a{i}, b{i} = v{i}",
                      f"    if type(a{i}) is not list or type(b{i}) is not list or len(a{i}) != {cols} "
                      f"or len(b{i}) != {cols}:",
                      f"        {fail}"]
            grouped[kind] += [f"*a{i}", f"*b{i}"]
        elif kind == "count":
            lines += [f"    if type(v{i}) is not int or not -MAX_INT64 <= v{i} <= MAX_INT64:",
                      f"        {fail}"]
            counts.append(f"v{i}")
        elif kind == "flag":
            lines += [f"    if type(v{i}) is not bool:", f"        {fail}"]
            flags.append(f"v{i}")
        else:  # label
            lines += [f"    if type(v{i}) is not str:", f"        {fail}"]
            labels.append(i)
    floats = ["vel_r", "vel_l", "*est", *grouped["scalar"], *grouped["vector2"], *grouped["points"]]
    # every double of the record at once: the command, the estimate, the scalars, vectors and points
    lines += [f"    floats = ({', '.join(floats)},)",
              "    if set(map(type, floats)) != FLOATS:",
              f"        {fail}",
              "    try:",
              "        text = state.encode()"]
    lines += [f"        t{i} = v{i}.encode()" for i in labels]
    lines += ["    except UnicodeEncodeError:  # a lone surrogate",
              f"        {fail}",
              "    if len(text) > STATE_BYTES" + "".join(f" or len(t{i}) > LABEL_BYTES" for i in labels)
              + ":",
              f"        {fail}"]
    size = "FIXED + len(text)" + "".join(f" + len(t{i})" for i in labels)
    fields = ["ANSWER", "rid", size, "*floats[:5]", "len(text)", "presence", "*floats[5:]", *counts,
              f"bytes(({''.join(f + ', ' for f in flags)}))", *(f"len(t{i})" for i in labels)]
    tail = " + text" + "".join(f" + t{i}" for i in labels)
    lines += [f"    return PACK({', '.join(fields)}){tail}"]
    return lines


def _decoder(layout: Any, framed: bool) -> str:
    """`decode(payload)`, or with `framed` `decode_frame(data, rid)`: the same checks and values on a whole
    frame whose header is unpacked with the fixed part (None where `data` is not exactly one answer record
    of request `rid` at least as long as the fixed part: the caller reads it frame by frame instead)."""
    signals = _kinds(layout)
    h = 3 if framed else 0                  # the header's fields come first in a framed unpacking
    data, fixed_end = ("data", "HEAD + FIXED") if framed else ("payload", "FIXED")  # the strings' start
    flags_at, labels_at = layout._flags_at + h, layout._labels_at + h  # noqa: SLF001
    if framed:
        lines = [
            "def decode_frame(data, rid, checked=None):",
            "    size = len(data) - HEAD",
            "    if size < FIXED:",
            "        return None",
            "    raw = UNPACK_FRAME(data)",
            "    if raw[0] != ANSWER or raw[1] != rid or raw[2] != size:",
            "        return None",
            "    if size > MAX:",
        ]
    else:
        lines = [
            "def decode(payload):",
            "    size = len(payload)",
            "    if not FIXED <= size <= MAX:",
        ]
    lines += [
        "        raise ProtocolError(f'a step record of {size} bytes, where this run\\'s layout takes '",
        "                            f'{FIXED} to {MAX}')",
    ]
    if not framed:
        lines += ["    raw = UNPACK(payload)"]
    lines += [f"    state_len, presence = raw[{5 + h}], raw[{6 + h}]"]
    bad_bits = "presence.translate(None, BITS)"
    if layout._flags:  # noqa: SLF001
        bad_bits += f" or raw[{flags_at}].translate(None, BITS)"
    lines += [f"    if {bad_bits}:",
              "        raise ProtocolError('a presence or flag byte other than 0 or 1 in a step record')",
              "    if state_len > STATE_BYTES:",
              "        raise ProtocolError('a string in a step record longer than its cap')",
              "    taken = FIXED + state_len"]
    labels = [(i, labels_at + k) for k, (i, _n, _kind, _c) in
              enumerate(s for s in signals if s[2] == "label")]
    for i, at in labels:
        lines += [f"    n{i} = raw[{at}]",
                  f"    if n{i} > LABEL_BYTES:",
                  "        raise ProtocolError('a string in a step record longer than its cap')",
                  f"    if n{i} and not presence[{i}]:",
                  "        raise ProtocolError('a length for an absent label in a step record')",
                  f"    taken += n{i}"]
    lines += ["    if taken != size:",
              "        raise ProtocolError(f'a step record of {size} bytes whose fields take {taken}')",
              "    # the frame is whole and well-formed: now its values",
              f"    end = {fixed_end} + state_len",
              "    try:",
              f"        state = str({data}[{fixed_end}:end], 'utf-8')"]
    for i, _at in labels:
        lines += [f"        t{i} = str({data}[end:end + n{i}], 'utf-8')", f"        end += n{i}"]
    lines += ["    except UnicodeDecodeError:",
              "        raise ProtocolError('a string in a step record that is not UTF-8') from None"]
    at, count_at, flag = layout._floats + h, layout._counts_at + h, 0  # noqa: SLF001
    where = {}  # the first double of each scalar, vector and points signal: grouped by kind in the record
    for group, width in (("scalar", 1), ("vector2", 2), ("points", 2)):
        for i, _name, kind, cols in signals:
            if kind == group:
                where[i], at = at, at + width * (cols if kind == "points" else 1)
    entries = []
    for i, name, kind, cols in signals:
        if kind == "scalar":
            value = f"raw[{where[i]}]"
        elif kind == "vector2":
            value = f"[raw[{where[i]}], raw[{where[i] + 1}]]"
        elif kind == "points":
            first = ", ".join(f"raw[{k}]" for k in range(where[i], where[i] + cols))
            second = ", ".join(f"raw[{k}]" for k in range(where[i] + cols, where[i] + 2 * cols))
            value = f"[[{first}], [{second}]]"
        elif kind == "count":
            value, count_at = f"raw[{count_at}]", count_at + 1
        elif kind == "flag":
            value, flag = f"raw[{flags_at}][{flag}] == 1", flag + 1
        else:
            value = f"t{i}"
        entries.append(f"{name!r}: {value}")
    lines += ["    debug = {" + ", ".join(entries) + "}",
              "    if presence != ALL:",
              "        for name, present in zip(NAMES, presence):",
              "            if not present:",
              "                debug[name] = None"]
    command = (("vel_r", f"raw[{h}]"), ("vel_l", f"raw[{h + 1}]"),  # the answer's items, for both returns
               ("estimate", f"[raw[{h + 2}], raw[{h + 3}], raw[{h + 4}]]"),
               ("state", "state"), ("debug", "debug"))
    if framed:
        lines += _checked_lines(layout, h, [i for i, _at in labels],
                                ", ".join(f"{key}={value}" for key, value in command))
    lines += ["    return {" + ", ".join(f"{key!r}: {value}" for key, value in command) + "}"]
    return "\n".join(lines)


def _checked_lines(layout: Any, h: int, labels: list[int], items: str) -> list[str]:
    """The framed decoder's test that its answer is already its validated command (simiam.brain's
    validate_command and simiam.signals' rules would give every value back as it is), and the
    `checked(...)` it then returns: the command's and the scalars' and vectors' doubles of a finite sum
    (so each is finite), each row of each points signal of a finite `sum` (the points rule's own test),
    the state and the labels at most their character caps long in bytes, the counts from 0 to MAX_COUNT.
    A value that fails (even one of an absent signal's slot) only sends the answer the long way."""
    if any(n > MAX_POINTS for _name, _at, n in layout._points_at):  # noqa: SLF001
        return []  # the points rule refuses such rows whatever they hold: always the long way
    first, end = layout._floats + h, layout._vectors_at + h + 2 * len(layout._vectors)  # noqa: SLF001
    total = f"sum(raw[{h}:{h + 5}])" + (f" + sum(raw[{first}:{end}])" if end > first else "")
    tests = ["state_len <= STATE_CHARS", *(f"n{i} <= LABEL_CHARS" for i in labels),
             *(f"0 <= raw[{layout._counts_at + h + k}] <= MAX_COUNT"  # noqa: SLF001
               for k in range(len(layout._counts)))]  # noqa: SLF001
    lines = ["    if checked is not None and " + " and ".join(tests) + ":",
             f"        total = {total}",
             "        finite = total - total == 0.0"]
    for k, (_name, at, n) in enumerate(layout._points_at):  # noqa: SLF001
        lines += ["        if finite:",
                  f"            xs{k} = sum(raw[{at + h}:{at + h + n}])",
                  f"            ys{k} = sum(raw[{at + h + n}:{at + h + 2 * n}])",
                  f"            finite = xs{k} - xs{k} == 0.0 and ys{k} - ys{k} == 0.0"]
    lines += ["        if finite:",
              f"            command = checked({items})",
              "            command.of = OF",
              "            return command"]
    return lines
