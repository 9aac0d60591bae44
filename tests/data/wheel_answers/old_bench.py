# WRONG VERSION kept for tests/packaging/test_answer_search.py: simiam/bench.py with the flat baseline loop (uni_to_diff, odometry and the IR conversion inline)
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
from simiam.machine import load_after_line, load_average, machine_line, ratio
from simiam.robot.ir_sensor import VOLTAGE_COEFFS, mounted_cone
from simiam.course.weeks import spec_for_week
from simiam.simulator import Simulator
from simiam.world import load_world


def _simulator(dt: float) -> Simulator:
    spec = spec_for_week(4)
    brain = instructor_tool("reference_brains").AvoidObstaclesBrain(spec)
    return Simulator(load_world("week4"), brain, spec, dt=dt)


def baseline_steps(n: int, dt: float = 0.033) -> float:
    """Run `n` baseline steps; returns a checksum (so the work cannot be skipped).

    Each step does, inline on local floats, what one simulator step computes: the exact-arc move and two
    encoders; the brain's odometry, five IR distances and world points, heading PID and ensure_w; the
    transform of the 30 cone and 13 plate points, five voltage polynomials and one edge-crossing formula
    (about what the culled physics evaluates per step in this world).
    """
    spec = spec_for_week(4)
    R, L, tpr = spec.wheel_radius, spec.wheel_base_length, spec.ticks_per_rev
    vmax, vmin = spec.max_vel, spec.min_vel
    m_per_tick = 2 * math.pi * R / tpr
    mounts = [(mx, my, math.cos(mt), math.sin(mt)) for mx, my, mt in spec.ir_mounts]
    points = [p for m in spec.ir_mounts for p in mounted_cone(m, spec.ir_max_range, spec.ir_spread)]
    points += list(spec.base_plate)
    cos, sin, atan2, floor = math.cos, math.sin, math.atan2, math.floor
    x = y = th = xe = ye = the = 0.0
    vr = vl = 0.0
    res_r = res_l = 0.0
    ticks_r = ticks_l = prev_r = prev_l = 0
    e_sum = e_prev = 0.0
    raws = [133, 200, 400, 200, 133]
    gains = (1.0, 1.0, 0.5, 1.0, 1.0)
    check = 0.0
    for _ in range(n):
        # (a) move: the exact arc, then the encoders
        v = R / 2 * (vr + vl)
        w = R / L * (vr - vl)
        half = w * dt / 2
        chord = v * dt * (sin(half) / half if half else 1.0)
        x += chord * cos(th + half)
        y += chord * sin(th + half)
        th += w * dt
        res_r += vr * dt
        k = floor(res_r * tpr / (2 * math.pi) + 0.5)
        res_r -= k * 2 * math.pi / tpr
        ticks_r += k
        res_l += vl * dt
        k = floor(res_l * tpr / (2 * math.pi) + 0.5)
        res_l -= k * 2 * math.pi / tpr
        ticks_l += k
        # (b) the brain: odometry, IR points, PID, ensure_w
        d_r = (ticks_r - prev_r) * m_per_tick
        d_l = (ticks_l - prev_l) * m_per_tick
        prev_r, prev_l = ticks_r, ticks_l
        d_c = (d_r + d_l) / 2
        t_new = the + (d_r - d_l) / L
        xe += d_c * cos(the)
        ye += d_c * sin(the)
        the = atan2(sin(t_new), cos(t_new))
        c, s = cos(the), sin(the)
        u_x = u_y = 0.0
        for raw, g, (mx, my, mc, ms) in zip(raws, gains, mounts, strict=True):
            volt = raw * 3 / 1000
            d = 0.0
            for coeff in VOLTAGE_COEFFS:  # the brain's own fifth-degree polynomial: the same arithmetic
                d = d * volt + coeff
            sx, sy = mx + d * mc, my + d * ms
            u_x += g * (c * sx - s * sy)
            u_y += g * (s * sx + c * sy)
        e = atan2(u_y, u_x) - the
        e = atan2(sin(e), cos(e))
        e_sum += e * dt
        w_cmd = 5.0 * e + 0.01 * e_sum + 0.01 * (e - e_prev) / dt
        e_prev = e
        v_lim = max(min(0.1, R * vmax), R * vmin)
        w_lim = max(min(abs(w_cmd), R / L * (vmax - vmin)), 0)
        vr = (2 * v_lim + w_lim * L) / (2 * R)
        vl = (2 * v_lim - w_lim * L) / (2 * R)
        if max(vr, vl) > vmax:
            shift = max(vr, vl) - vmax
            vr, vl = vr - shift, vl - shift
        if w_cmd < 0:
            vr, vl = vl, vr
        # (d) physics: the robot's points in the world, the IR voltages, one crossing test
        c, s = cos(th), sin(th)
        xs = [c * px - s * py + x for px, py in points]
        ys = [s * px + c * py + y for px, py in points]
        for i in range(5):
            d = 0.04 + 0.05 * i
            volt = 0.0
            for coeff in VOLTAGE_COEFFS:
                volt = volt * d + coeff
            raws[i] = min(max(floor(volt * 1000 / 3 + 0.5), 133), 917)
        x1, y1, x21, y21 = xs[0], ys[0], xs[3] - xs[0], ys[3] - ys[0]
        x43, y43 = 0.0, 1.0
        den = y43 * x21 - x43 * y21
        if den != 0.0:
            ua = (x43 * (y1 - 0.5) - y43 * (x1 - 0.5)) / den
            check += ua
    return check + x + y + th


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
