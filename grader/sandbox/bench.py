"""Sandbox overhead figures: worker start (bubblewrap vs plain subprocess) and round trips per call.

    python -m grader.sandbox.bench [--starts 10] [--calls 2000] [--week 3]

Prints, per isolation mode available here: the median and worst start time of a worker (bootstrap,
privilege drop, preloading numpy and simiam, loading the submission), the round trip of a `ping`, and the
round trip of a `brain_step` running the reference solution's supervisor (microseconds per call).
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

from grader.sandbox.isolation import BWRAP, SUBPROCESS, bwrap_works
from grader.sandbox.session import StudentSession

ROOT = Path(__file__).resolve().parents[2]


def _readings(k: int, dt: float) -> dict:
    return {"t": k * dt, "dt": dt, "ticks": [k, k], "ir_raw": [200, 200, 200, 200, 200]}


def measure(mode: str, week: int, starts: int, calls: int) -> dict:
    """Start `starts` fresh workers, then time `calls` pings and brain steps on one of them."""
    folder = ROOT / "solutions" / f"week{week}"
    start_times = []
    for _ in range(starts):
        with StudentSession(week, folder, sandbox=mode) as session:
            began = time.perf_counter()
            session.load()
            start_times.append(time.perf_counter() - began)
    with StudentSession(week, folder, sandbox=mode) as session:
        session.load()
        began = time.perf_counter()
        for _ in range(calls):
            session.call("ping")
        ping = (time.perf_counter() - began) / calls
        session.call("brain_start", settings=None)
        began = time.perf_counter()
        for k in range(calls):
            session.call("brain_step", readings=_readings(k, 0.033))
        step = (time.perf_counter() - began) / calls
    return {"mode": mode, "start_median_s": statistics.median(start_times), "start_max_s": max(start_times),
            "ping_us": ping * 1e6, "brain_step_us": step * 1e6}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, default=10)
    parser.add_argument("--calls", type=int, default=2000)
    parser.add_argument("--week", type=int, default=3)
    args = parser.parse_args(argv)
    modes = [BWRAP, SUBPROCESS] if bwrap_works()[0] else [SUBPROCESS]
    for mode in modes:
        r = measure(mode, args.week, args.starts, args.calls)
        start_ms, max_ms = r["start_median_s"] * 1000, r["start_max_s"] * 1000
        print(f"{r['mode']:10}  start {start_ms:6.1f} ms median, {max_ms:6.1f} ms max ({args.starts} starts)"
              f"   ping {r['ping_us']:6.1f} us   brain_step {r['brain_step_us']:6.1f} us"
              f" ({args.calls} calls, week {args.week} solution)")


if __name__ == "__main__":
    main()
