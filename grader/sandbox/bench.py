"""Sandbox overhead figures: worker start (bubblewrap vs plain subprocess) and round trips per call.

    python -m grader.sandbox.bench [--starts 10] [--calls 2000] [--week 3]

Prints the machine line, then per isolation mode available here: the median and worst start time of a
worker (bootstrap, privilege drop, preloading numpy and simiam, loading the submission) in wall and CPU
seconds (the worker's CPU counted once it has been reaped), the round trip of a `ping` and of a
`brain_step` running the reference solution's supervisor (microseconds per call, wall and CPU). The
baselines, measured in the same run: a bare interpreter start (`python -I -S -c pass`) and a round trip
of the same JSON message through a pipe pair to a child that only echoes it. Ratios to them are what
stays comparable between machines and under load.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from grader.sandbox.isolation import BWRAP, SUBPROCESS, bwrap_works
from grader.sandbox.session import StudentSession
from simiam.machine import (
    Stopwatch,
    Usage,
    descendants_cpu,
    load_after_line,
    machine_line,
    median_usage,
    prepare_bytecode,
    ratio,
)

ROOT = Path(__file__).resolve().parents[2]

# The echo child of the round-trip baseline: copies its stdin to its stdout, nothing else.
_ECHO = "import os\nwhile True:\n    d = os.read(0, 65536)\n    if not d: break\n    os.write(1, d)\n"


def _readings(k: int, dt: float) -> dict:
    return {"t": k * dt, "dt": dt, "ticks": [k, k], "ir_raw": [200, 200, 200, 200, 200]}


def sandbox_description(sandbox: str = "auto") -> str:
    """What isolation a worker gets here with `sandbox` (auto, bwrap, subprocess), in words."""
    if sandbox == SUBPROCESS:
        return "plain subprocess (chosen)"
    works, why = bwrap_works()
    return "bubblewrap" if works else f"plain subprocess (bubblewrap unusable: {why})"


def interpreter_start(runs: int = 5) -> Usage:
    """Median wall and CPU seconds of `python -I -S -c pass`: the floor under any worker start."""
    usages = []
    for _ in range(runs):
        with Stopwatch() as sw:
            subprocess.run([sys.executable, "-I", "-S", "-c", "pass"], check=True)
        usages.append(sw.usage)
    return median_usage(usages)


def worker_start(week: int, folder: Path, mode: str) -> Usage:
    """Wall and CPU seconds (grader and worker) of starting a worker, loading `folder`, closing it."""
    with Stopwatch() as sw, StudentSession(week, folder, sandbox=mode) as session:
        session.load()
    return sw.usage


def bare_worker_start(week: int, mode: str) -> Usage:
    """A worker started on an empty submission: the sandbox and the trusted preloads, no student code."""
    with tempfile.TemporaryDirectory(prefix="simiam-bench-empty-") as empty:
        return worker_start(week, Path(empty), mode)


def echo_round_trip(calls: int, start: Usage) -> Usage:
    """`calls` round trips of a JSON ping through a pipe pair to an echo child (encode, write, read,
    decode), per call. The CPU counts both processes; the child's start (`start`, an interpreter start
    measured just before) is taken off."""
    message = json.dumps({"id": 1, "op": "ping"}, separators=(",", ":")).encode() + b"\n"
    with Stopwatch() as sw:
        child = subprocess.Popen([sys.executable, "-I", "-S", "-c", _ECHO], stdin=subprocess.PIPE,
                                 stdout=subprocess.PIPE)
        assert child.stdin is not None and child.stdout is not None
        write_fd, read_fd = child.stdin.fileno(), child.stdout.fileno()
        with Stopwatch(follow_children=False) as calls_only:
            for _ in range(calls):
                os.write(write_fd, message)
                json.loads(os.read(read_fd, 65536))
        child.stdin.close()
        child.wait()
    child_cpu = max(0.0, sw.usage.cpu_children - start.cpu_children)
    return Usage(calls_only.usage.wall / calls, calls_only.usage.cpu_self / calls, child_cpu / calls)


def measure(mode: str, week: int, starts: int, calls: int) -> dict:
    """Start `starts` fresh workers, then time `calls` pings and brain steps on one worker each."""
    folder = ROOT / "solutions" / f"week{week}"
    start_usages = [worker_start(week, folder, mode) for _ in range(starts)]
    start = median_usage(start_usages)
    per_call = {}
    for op in ("ping", "brain_step"):
        with StudentSession(week, folder, sandbox=mode) as session:
            session.load()
            if op == "brain_step":
                session.call("brain_start", settings=None)
            worker_before = descendants_cpu()  # the live worker (and its bubblewrap parents)
            with Stopwatch(follow_children=False) as loop:
                for k in range(calls):
                    if op == "ping":
                        session.call("ping")
                    else:
                        session.call("brain_step", readings=_readings(k, 0.033))
            worker_cpu = descendants_cpu() - worker_before
        per_call[op] = Usage(loop.usage.wall / calls, loop.usage.cpu_self / calls, worker_cpu / calls)
    return {"mode": mode, "start": start, "start_max_wall": max(u.wall for u in start_usages),
            "ping": per_call["ping"], "brain_step": per_call["brain_step"]}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, default=10)
    parser.add_argument("--calls", type=int, default=2000)
    parser.add_argument("--week", type=int, default=3)
    args = parser.parse_args(argv)
    if args.starts < 1 or args.calls < 1:
        parser.error("--starts and --calls must be at least 1")
    print(machine_line(sandbox_description()), flush=True)
    print(prepare_bytecode(), flush=True)
    python = interpreter_start()
    echo = echo_round_trip(args.calls, python)
    print(f"baseline    interpreter start {python.wall * 1000:6.1f} ms wall, {python.cpu * 1000:6.1f} ms CPU"
          f"   echo round trip {echo.wall * 1e6:6.1f} us wall, {echo.cpu * 1e6:6.1f} us CPU", flush=True)
    modes = [BWRAP, SUBPROCESS] if bwrap_works()[0] else [SUBPROCESS]
    for mode in modes:
        r = measure(mode, args.week, args.starts, args.calls)
        start, ping, step = r["start"], r["ping"], r["brain_step"]
        print(f"{mode:10}  start {start.wall * 1000:6.1f} ms median ({r['start_max_wall'] * 1000:.1f} max), "
              f"{start.cpu * 1000:6.1f} ms CPU = {ratio(start.cpu, python.cpu):.1f}x an interpreter start"
              f" ({args.starts} starts, week {args.week} solution)")
        for name, u in (("ping", ping), ("brain_step", step)):
            print(f"{'':10}  {name:10} {u.wall * 1e6:6.1f} us wall, {u.cpu * 1e6:6.1f} us CPU = "
                  f"{ratio(u.cpu, echo.cpu):.1f}x the echo round trip ({args.calls} calls)", flush=True)
    print(load_after_line())


if __name__ == "__main__":
    main()
