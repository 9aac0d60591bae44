"""The worker's answer record, written straight from the robot and the supervisor (issue 32).

A step's answer used to be built as the dict `LocalBrain.answer` returns (lists and a dict of debug
values), then walked again by the record's encoder: two passes over every value, each step, on a core the
worker shares with the grader, where each pass runs cold. `compile_writer` generates, once per run, one
function that reads the same things in the same order as `LocalBrain.answer` (the wheel speeds, the
estimate, the state, then the current controller and each declared signal with the same readers as
simiam.signals.read_signals) and goes on with the encoder's own checks and packing
(grader.inside.record_codec.pack_lines) on those values. Where a value is not of its record type, it
returns the dict `LocalBrain.answer` would have returned from those same values (read once: a student's
property is never read twice), which the worker sends as JSON, as before records.

Like everything in the worker, it only makes honest answers cheap: the grader checks every record
(step_record.StepLayout.decode_answer) whatever wrote it. The generated source holds only the layout's
positions and, as `repr` literals, attribute names from the trusted signal registry; `writer_source`
shows it.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from types import CodeType
from typing import Any

from grader.inside.record_codec import namespace, pack_lines
from simiam.signals import declared, plain, read_plan

Writer = Callable[[int], "bytes | dict"]


def writer_source(layout: Any) -> str:
    """The Python source of `layout`'s writer (function `write(rid)`) and its fallback."""
    plan = read_plan(declared(layout.names), layout.n_ir)
    values = [f"v{i}" for i in range(len(plan))]
    fallback = "return FALLBACK(vel_r, vel_l, est, state, got)"
    lines = [
        "def FALLBACK(vel_r, vel_l, est, state, got):",
        "    return {'vel_r': vel_r, 'vel_l': vel_l, 'estimate': est, 'state': state,",
        "            'debug': dict(zip(NAMES, got))}",
        "",
        "",
        "def write(rid):",
        "    vel_r = plain(ROBOT.vel_r)",
        "    vel_l = plain(ROBOT.vel_l)",
        "    est = [plain(c) for c in SUP.state_estimate.unpack()]",
        "    state = str(SUP.current_state)",
        "    ctl = getattr(SUP, 'current_controller', None)",
    ]
    for i, (_name, of_controller, attr, index, _reader, n) in enumerate(plan):
        owner = "ctl" if of_controller else "SUP"
        if index is None:
            lines += [f"    v{i} = getattr({owner}, {attr!r}, None)",
                      f"    if v{i} is not None:",  # as read_signals: a reader gives None for None
                      f"        v{i} = R{i}(v{i}, {n})"]
        else:  # read_signals' indexing: any exception of the student's object means None
            lines += [f"    x{i} = getattr({owner}, {attr!r}, None)",
                      f"    if x{i} is not None:",
                      "        try:",
                      f"            x{i} = x{i}[{index!r}]",
                      "        except Exception:",
                      f"            x{i} = None",
                      f"    v{i} = None if x{i} is None else R{i}(x{i}, {n})"]
    lines += [f"    got = ({''.join(v + ', ' for v in values)})",  # as read, before absent ones are zeroed
              "    if len(est) != 3 or type(state) is not str:",
              f"        {fallback}"]
    return "\n".join(lines + pack_lines(layout, fallback))


def compile_writer(layout: Any, caps: dict[str, Any], brain: Any) -> Writer:
    """The writer of `layout` for `brain` (a LocalBrain whose signals and IR count are the layout's):
    `write(rid)` is `encode_answer(rid, brain.answer())`, or `brain.answer()` itself where that encoding
    is None (see the module docstring)."""
    plan = read_plan(declared(layout.names), layout.n_ir)
    space = {**namespace(layout, caps), "plain": plain, "ROBOT": brain.robot, "SUP": brain.supervisor,
             **{f"R{i}": entry[4] for i, entry in enumerate(plan)}}
    exec(_compiled(writer_source(layout), f"<step record writer {','.join(layout.names)} {layout.n_ir}>"),  # noqa: S102
         space)
    return space["write"]


@functools.lru_cache(maxsize=16)
def _compiled(source: str, name: str) -> CodeType:
    """`source` compiled once per process (a run's brain_start is charged to the student: ~1-2 ms saved)."""
    return compile(source, name, "exec")
