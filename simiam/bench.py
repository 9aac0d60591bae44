"""`simiam bench`: steps per second of one QuickBot with five IR sensors in the week-4 world, driven by a
small trusted avoid-obstacles brain (instructor_tools.reference_brains, in the course checkout only; a
student package says so and exits 2) (odometry, the five IR points, gains [1, 1, 0.5, 1, 1], PID on the
heading, the week-4 ensure_w). The figure covers physics and brain; a second figure adds Trace recording."""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time

from simiam.course.folders import NotInCheckout, instructor_tool
from simiam.robot.quickbot import spec_for_week
from simiam.simulator import Simulator
from simiam.world import load_world


def _simulator(dt: float) -> Simulator:
    spec = spec_for_week(4)
    brain = instructor_tool("reference_brains").AvoidObstaclesBrain(spec)
    return Simulator(load_world("week4"), brain, spec, dt=dt)


def measure(seconds: float = 60.0, repeats: int = 5, dt: float = 0.033) -> dict:
    """Best-of-`repeats` timing of `seconds` simulated seconds; step loop alone and with a Trace."""
    n = int(round(seconds / dt))
    best_step = best_cpu = math.inf
    collisions = 0
    for _ in range(repeats):
        sim = _simulator(dt)
        t0 = time.perf_counter()
        c0 = time.thread_time()
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
            "load_average_1min": os.getloadavg()[0] if hasattr(os, "getloadavg") else None,
            "runs_with_collision": collisions, "final_pose": list(sim.pose),
            "world": "week4", "brain": "reference avoid_obstacles (pure Python)"}


def main(args: argparse.Namespace) -> int:
    """Entry point of `simiam bench [--json] [--seconds T]`."""
    seconds = getattr(args, "seconds", None)
    seconds = 60.0 if seconds is None else seconds
    if not (math.isfinite(seconds) and 0 < seconds <= 3600):
        print(f"simiam bench: --seconds must be between 0 and 3600, got {seconds:g}", file=sys.stderr)
        return 2
    try:
        res = measure(seconds=seconds)
    except NotInCheckout as exc:
        # The benchmark drives the reference avoid-obstacles controller: a full solution of week 4.
        print(f"simiam bench: {exc}", file=sys.stderr)
        return 2
    if getattr(args, "json", False):
        print(json.dumps(res))
        return 0
    print(f"simiam bench: one QuickBot, 5 IR sensors, week-4 world, reference avoid-obstacles brain, "
          f"dt = {res['dt']} s, {res['steps']} steps x {res['repeats']} (best)")
    print(f"  {res['steps_per_second']:,.0f} steps/s  ({res['us_per_step']:.1f} us/step, "
          f"{res['real_time_factor']:,.0f}x real time)")
    print(f"  {res['with_trace_steps_per_second']:,.0f} steps/s including Trace recording")
    if res["cpu_steps_per_second"]:
        print(f"  {res['cpu_steps_per_second']:,.0f} steps/s by thread CPU time "
              f"(load average {res['load_average_1min']:.2f}; wall-clock drops above {os.cpu_count()})")
    if res["runs_with_collision"]:
        print(f"  note: the robot collided in {res['runs_with_collision']} of {res['repeats']} runs")
    return 0
