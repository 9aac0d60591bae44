"""`simiam bench`: steps per second of one QuickBot with five IR sensors in the week-4 world, driven by a
small trusted avoid-obstacles brain (instructor_tools.reference_brains, in the course checkout only; a
student package says so and exits 2) (odometry, the five IR points, gains [1, 1, 0.5, 1, 1], PID on the
heading, the week-4 ensure_w). The figure covers physics and brain; a second figure adds Trace recording.

Next to it runs a baseline in the same process: `baseline_steps`, one flat Python loop doing a step's
arithmetic with nothing in between (no objects, dicts, validation or culling structure). The ratio
simulator / baseline stays about the same on machines 2-3x apart in speed, and under load, where the raw
steps per second do not; the CPU-time figures are the ones to compare on a shared machine.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time

from simiam.course.folders import NotInCheckout, instructor_tool
from simiam.course.weeks import spec_for_week
from simiam.machine import load_after_line, load_average, machine_line, ratio
from simiam.simulator import Simulator
from simiam.world import load_world


def _simulator(dt: float) -> Simulator:
    spec = spec_for_week(4)
    brain = instructor_tool("reference_brains").AvoidObstaclesBrain(spec)
    return Simulator(load_world("week4"), brain, spec, dt=dt)


def baseline_steps(n: int, dt: float = 0.033) -> float:
    """`n` steps of the flat baseline loop (instructor_tools.bench_baseline: it holds the answers of weeks
    2-4 inline, so only the course checkout has it); returns its checksum."""
    return float(instructor_tool("bench_baseline").baseline_steps(n, dt))


def measure(seconds: float = 60.0, repeats: int = 5, dt: float = 0.033) -> dict:
    """Best-of-`repeats` timing of `seconds` simulated seconds (step loop alone and with a Trace), and of
    as many baseline steps, interleaved so that both see the same load. Wall and thread CPU time."""
    n = int(round(seconds / dt))
    best_step = best_cpu = best_base = best_base_cpu = math.inf
    collisions = 0
    load_before = load_average()
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.thread_time()
        baseline_steps(n, dt)
        best_base_cpu = min(best_base_cpu, time.thread_time() - c0)
        best_base = min(best_base, time.perf_counter() - t0)
        sim = _simulator(dt)
        t0, c0 = time.perf_counter(), time.thread_time()
        for _ in range(n):
            sim.step()
        best_cpu = min(best_cpu, time.thread_time() - c0)
        best_step = min(best_step, time.perf_counter() - t0)
        collisions += sim.first_collision is not None
    best_run = math.inf
    for _ in range(repeats):
        sim = _simulator(dt)
        t0 = time.perf_counter()
        trace = sim.run(seconds, stop_on_collision=False)
        best_run = min(best_run, time.perf_counter() - t0)
    us = best_step / n * 1e6
    return {"steps_per_second": n / best_step, "us_per_step": us, "steps": n, "dt": dt,
            "real_time_factor": dt / (us * 1e-6), "seconds_simulated": n * dt, "repeats": repeats,
            "with_trace_steps_per_second": (len(trace) - 1) / best_run,
            # CPU time of this thread: what one core delivers even when the machine is oversubscribed
            "cpu_steps_per_second": n / best_cpu if best_cpu > 0 else None,
            "cpu_us_per_step": best_cpu / n * 1e6,
            "baseline_us_per_step": best_base / n * 1e6, "baseline_cpu_us_per_step": best_base_cpu / n * 1e6,
            "ratio_to_baseline": ratio(best_step, best_base),
            "cpu_ratio_to_baseline": ratio(best_cpu, best_base_cpu),
            "load_average_before": load_before, "load_average_after": load_average(),
            "load_average_1min": None if load_before is None else load_before[0],
            "runs_with_collision": collisions, "final_pose": list(sim.pose),
            "world": "week4", "brain": "reference avoid_obstacles (pure Python)"}


def main(args: argparse.Namespace) -> int:
    """Entry point of `simiam bench [--json] [--seconds T]`."""
    seconds = getattr(args, "seconds", None)
    seconds = 60.0 if seconds is None else seconds
    if not (math.isfinite(seconds) and 0 < seconds <= 3600):
        print(f"simiam bench: --seconds must be between 0 and 3600, got {seconds:g}", file=sys.stderr)
        return 2
    machine = machine_line("none (trusted code only)")
    try:
        res = measure(seconds=seconds)
    except NotInCheckout as exc:
        # The benchmark drives the reference avoid-obstacles controller: a full solution of week 4.
        print(f"simiam bench: {exc}", file=sys.stderr)
        return 2
    if getattr(args, "json", False):
        print(json.dumps(dict(res, machine=machine)))
        return 0
    print(machine)
    print(f"simiam bench: one QuickBot, 5 IR sensors, week-4 world, reference avoid-obstacles brain, "
          f"dt = {res['dt']} s, {res['steps']} steps x {res['repeats']} (best)")
    print(f"  {res['steps_per_second']:,.0f} steps/s  ({res['us_per_step']:.1f} us/step wall, "
          f"{res['cpu_us_per_step']:.1f} us/step CPU, {res['real_time_factor']:,.0f}x real time)")
    print(f"  {res['with_trace_steps_per_second']:,.0f} steps/s including Trace recording")
    print(f"  baseline (a step's arithmetic in one flat loop): {res['baseline_us_per_step']:.1f} us/step "
          f"wall, {res['baseline_cpu_us_per_step']:.1f} us/step CPU")
    print(f"  simulator / baseline: {res['cpu_ratio_to_baseline']:.2f}x by CPU time "
          f"({res['ratio_to_baseline']:.2f}x by wall time): compare this ratio between machines")
    if res["runs_with_collision"]:
        print(f"  note: the robot collided in {res['runs_with_collision']} of {res['repeats']} runs")
    print(load_after_line())
    return 0
