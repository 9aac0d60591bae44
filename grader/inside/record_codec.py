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
from simiam.signals import declared

Encoder = Callable[[int, Any], "bytes | None"]
Decoder = Callable[[bytes], dict]


def source(layout: Any) -> str:
    """The Python source of `layout`'s encoder and decoder (functions `encode` and `decode`)."""
    return _encoder(layout) + "\n\n" + _decoder(layout)


def compile_codec(layout: Any, caps: dict[str, Any]) -> tuple[Encoder, Decoder]:
    """`layout`'s encoder and decoder (see the module docstring); `caps`: the record's STATE_BYTES,
    LABEL_BYTES, MAX_INT64 and BITS (the bytes a presence or flag byte may be)."""
    names = layout.names
    space: dict[str, Any] = {
        "ProtocolError": ProtocolError, "UnicodeDecodeError": UnicodeDecodeError,
        # header and fixed part in one struct: one pack per answer
        "PACK": struct.Struct(HEADER.format + layout.answer.format.lstrip("<")).pack,
        "UNPACK": layout.answer.unpack_from, "ANSWER": ANSWER, "FIXED": layout.answer.size,
        "MAX": layout.max_answer, **caps, "ALL": layout._all_present,  # noqa: SLF001
        "FLOATS": {float}, "NAMES": names,
        "ZERO": tuple(layout._zero[name] for name in names),  # noqa: SLF001
    }
    exec(compile(source(layout), f"<step record codec {','.join(names)} {layout.n_ir}>", "exec"), space)  # noqa: S102
    return space["encode"], space["decode"]


def _kinds(layout: Any) -> list[tuple[int, str, str, int]]:
    """(position in the declared order, name, kind, columns) of each signal."""
    return [(i, s.name, s.kind, s.columns(layout.n_ir)) for i, s in enumerate(declared(layout.names))]


def _encoder(layout: Any) -> str:
    signals = _kinds(layout)
    n = len(signals)
    lines = [
        "def encode(rid, answer):",
        "    if type(answer) is not dict:",
        "        return None",
        "    get = answer.get",
        "    est, state, debug = get('estimate'), get('state'), get('debug')",
        "    if type(est) is not list or len(est) != 3 or type(state) is not str \\",
        f"            or type(debug) is not dict or len(debug) != {n}:",
        "        return None",
    ]
    if n:
        lines += ["    try:",
                  "        " + "; ".join(f"v{i} = debug[{name!r}]" for i, name, _, _ in signals),
                  "    except KeyError:",
                  "        return None",
                  "    presence = ALL",
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
            lines += [f"    if type(v{i}) is not list or len(v{i}) != 2:", "        return None"]
            grouped[kind].append(f"*v{i}")
        elif kind == "points":
            lines += [f"    if type(v{i}) is not list or len(v{i}) != 2:", "        return None",
                      f"    a{i}, b{i} = v{i}",
                      f"    if type(a{i}) is not list or type(b{i}) is not list or len(a{i}) != {cols} "
                      f"or len(b{i}) != {cols}:",
                      "        return None"]
            grouped[kind] += [f"*a{i}", f"*b{i}"]
        elif kind == "count":
            lines += [f"    if type(v{i}) is not int or not -MAX_INT64 <= v{i} <= MAX_INT64:",
                      "        return None"]
            counts.append(f"v{i}")
        elif kind == "flag":
            lines += [f"    if type(v{i}) is not bool:", "        return None"]
            flags.append(f"v{i}")
        else:  # label
            lines += [f"    if type(v{i}) is not str:", "        return None"]
            labels.append(i)
    floats = ["get('vel_r')", "get('vel_l')", "*est", *grouped["scalar"], *grouped["vector2"],
              *grouped["points"]]
    # every double of the record at once: the command, the estimate, the scalars, vectors and points
    lines += [f"    floats = ({', '.join(floats)},)",
              "    if set(map(type, floats)) != FLOATS:",
              "        return None",
              "    try:",
              "        text = state.encode()"]
    lines += [f"        t{i} = v{i}.encode()" for i in labels]
    lines += ["    except UnicodeEncodeError:  # a lone surrogate",
              "        return None",
              "    if len(text) > STATE_BYTES" + "".join(f" or len(t{i}) > LABEL_BYTES" for i in labels)
              + ":",
              "        return None"]
    size = "FIXED + len(text)" + "".join(f" + len(t{i})" for i in labels)
    fields = ["ANSWER", "rid", size, "*floats[:5]", "len(text)", "presence", "*floats[5:]", *counts,
              f"bytes(({''.join(f + ', ' for f in flags)}))", *(f"len(t{i})" for i in labels)]
    tail = " + text" + "".join(f" + t{i}" for i in labels)
    lines += [f"    return PACK({', '.join(fields)}){tail}"]
    return "\n".join(lines)


def _decoder(layout: Any) -> str:
    signals = _kinds(layout)
    flags_at, labels_at = layout._flags_at, layout._labels_at  # noqa: SLF001
    lines = [
        "def decode(payload):",
        "    size = len(payload)",
        "    if not FIXED <= size <= MAX:",
        "        raise ProtocolError(f'a step record of {size} bytes, where this run\\'s layout takes '",
        "                            f'{FIXED} to {MAX}')",
        "    raw = UNPACK(payload)",
        "    state_len, presence = raw[5], raw[6]",
    ]
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
              "    end = FIXED + state_len",
              "    try:",
              "        state = str(payload[FIXED:end], 'utf-8')"]
    for i, _at in labels:
        lines += [f"        t{i} = str(payload[end:end + n{i}], 'utf-8')", f"        end += n{i}"]
    lines += ["    except UnicodeDecodeError:",
              "        raise ProtocolError('a string in a step record that is not UTF-8') from None"]
    at, count_at, flag = layout._floats, layout._counts_at, 0  # noqa: SLF001
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
              "                debug[name] = None",
              "    return {'vel_r': raw[0], 'vel_l': raw[1], 'estimate': [raw[2], raw[3], raw[4]], "
              "'state': state, 'debug': debug}"]
    return "\n".join(lines)
