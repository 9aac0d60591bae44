"""Instructions per scenario step of the channel's own code, JSON lines against step records, counted by
callgrind: a figure no load changes (issue 32; step_bench.py measures the whole step, under the load).

    python benchmarks/step_codec.py [--weeks 3 6] [--steps 2000]
    python benchmarks/step_codec.py --hot [--weeks 3 6]

For each week, one step's readings and the week's solution's answer (recorded from a LocalBrain run of the
week's `simiam run` scenario) go both ways through each codec, in one process: the grader's encoding of
the readings, the worker's decoding of them, the worker's encoding of the answer and the grader's decoding
and bounding of it (as before records: protocol.encode_request / decode_request, to_json + weigh + encode,
the LineReader's split + decode + check_message; with records: grader.inside.step_record's
encode_readings, decode_request, encode_answer and decode_frame, whole frames as a step takes them; in the
worker the answer's packing is the same code as encode_answer's, reading the supervisor instead of a dict:
grader.inside.record_writer). Each codec runs under `valgrind --tool=callgrind` twice, for `steps` and
3 x `steps` steps; the difference over 2 x `steps` is its instructions per step, start-up excluded.
System calls, the brain and the simulator are not in it.

`--hot` times each part of the records' codec instead (timeit, best of 7, one process, its code and data
warm in the caches): what a part costs at best, to set beside what the step costs where the two processes
take turns on one core (step_bench.py).
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def _sample(week_n: int) -> tuple[dict, dict, Any]:
    """One step's readings and the week's solution's answer (the middle step of a LocalBrain run of the
    week's `simiam run` scenario), and the week's step layout."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from step_bench import record

    from grader.inside.step_record import layout_for
    from simiam.course.weeks import get_week
    from simiam.signals import week_signals

    recorder = record(week_n, ROOT / "solutions" / f"week{week_n}")
    middle = len(recorder.answers) // 2
    week = get_week(week_n)
    return (recorder.readings[middle], recorder.answers[middle],
            layout_for(week_signals(week), len(week.spec.ir_mounts)))


def _loop(week_n: int, codec: str, steps: int) -> None:
    """Run inside valgrind: `steps` round trips of one step through `codec`."""
    from grader.inside.answer_bounds import check_message, weigh
    from grader.inside.protocol import FrameReader, decode, decode_request, encode, encode_request, to_json
    readings, answer, layout = _sample(week_n)
    if codec == "json":
        for k in range(steps):
            line = encode_request({"readings": readings, "id": k, "op": "brain_step"})
            request = decode_request(line)["readings"]
            value = to_json(answer)
            weigh(value)
            reader = FrameReader()
            reader.feed(encode({"id": k, "ok": True, "value": value}))
            message = decode(reader.pop())  # type: ignore[arg-type]
            check_message(message)
    else:
        for k in range(steps):  # as the grader and the worker take them: whole frames
            frame = layout.encode_readings(k, readings)
            rid, request = layout.decode_request(frame)  # type: ignore[arg-type,misc]
            reply = layout.encode_answer(rid, answer)
            assert reply is not None, "the solution's answer is not a record"
            layout.decode_frame(reply, k)
    assert request["ticks"] == readings["ticks"]


def _hot(week_n: int) -> dict[str, float]:
    """us per call of each part of the records' codec, warm (see the module docstring)."""
    import timeit

    from grader.inside.step_record import HEADER

    readings, answer, layout = _sample(week_n)
    request, reply = layout.encode_readings(1, readings), layout.encode_answer(1, answer)
    assert request is not None and reply is not None, "the solution's step is not a record"
    parts = {"encode_readings": lambda: layout.encode_readings(1, readings),
             "decode_request": lambda: layout.decode_request(request),
             "encode_answer": lambda: layout.encode_answer(1, answer),
             "decode_frame": lambda: layout.decode_frame(reply, 1),
             "struct_unpack_answer": lambda: layout.answer.unpack_from(reply, HEADER.size)}
    n = 20000
    return {name: round(min(timeit.repeat(part, number=n, repeat=7)) / n * 1e6, 2)
            for name, part in parts.items()}


def _instructions(week_n: int, codec: str, steps: int) -> int:
    done = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", sys.executable,
                           __file__, "--inner", str(week_n), codec, str(steps)],
                          capture_output=True, text=True, check=True)
    return int(re.search(r"Collected : (\d+)", done.stderr).group(1))  # type: ignore[union-attr]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--weeks", type=int, nargs="+", default=[3, 6])
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--hot", action="store_true", help="time the records' codec warm (us) instead")
    p.add_argument("--inner", nargs=3, help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.hot:
        for week_n in args.weeks:
            print(json.dumps({"week": week_n, "us": _hot(week_n)}), flush=True)
        return 0
    if args.inner:
        _loop(int(args.inner[0]), args.inner[1], int(args.inner[2]))
        return 0
    if shutil.which("valgrind") is None:
        print("valgrind is not installed: nothing to count", file=sys.stderr)
        return 2
    for week_n in args.weeks:
        per_step = {codec: (_instructions(week_n, codec, 3 * args.steps)
                            - _instructions(week_n, codec, args.steps)) / (2 * args.steps)
                    for codec in ("json", "records")}
        print(json.dumps({"week": week_n, **{k: round(v) for k, v in per_step.items()},
                          "records/json": round(per_step["records"] / per_step["json"], 3)}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
