"""`simiam bench`: steps per second of one QuickBot with five IR sensors in the week-4 world, driven by a
small trusted avoid-obstacles brain (odometry, the five IR points, gains [1, 1, 0.5, 1, 1], PID on the
heading, the week-4 ensure_w). The figure covers physics and brain; a second figure adds Trace recording."""

from __future__ import annotations

import json
import math
import time

from simiam.robot.dynamics import diff_to_uni, uni_to_diff
from simiam.robot.quickbot import RobotSpec, spec_for_week
from simiam.simulator import Simulator
from simiam.world import load_world

# polyfit(table_V, table_d, 5) rounded to 4 decimals, as the course's get_ir_distances (weeks 3+)
_P_INV = (-0.0182, 0.1690, -0.6264, 1.1853, -1.2104, 0.6293)
_GAINS = (1.0, 1.0, 0.5, 1.0, 1.0)


def _sign(x: float) -> float:
    return (x > 0) - (x < 0)


class AvoidObstaclesBrain:
    """A trusted reference brain for benchmarks: week-4 avoid-obstacles with the week-4 ensure_w."""

    def __init__(self, spec: RobotSpec, start: tuple[float, float, float] = (0.0, 0.0, 0.0), v: float = 0.1,
                 gains: tuple[float, float, float] = (5.0, 0.01, 0.01)) -> None:
        self.spec = spec
        self.x, self.y, self.theta = start
        self.prev = (0, 0)
        self.v = v
        self.kp, self.ki, self.kd = gains
        self.e_sum = 0.0
        self.e_prev = 0.0
        self.m_per_tick = 2 * math.pi * spec.wheel_radius / spec.ticks_per_rev
        self.mounts = [(mx, my, math.cos(mt), math.sin(mt)) for mx, my, mt in spec.ir_mounts]

    def _odometry(self, ticks: list[int]) -> None:
        d_r = (ticks[0] - self.prev[0]) * self.m_per_tick
        d_l = (ticks[1] - self.prev[1]) * self.m_per_tick
        self.prev = (ticks[0], ticks[1])
        d_c = (d_r + d_l) / 2
        theta_new = self.theta + (d_r - d_l) / self.spec.wheel_base_length
        self.x += d_c * math.cos(self.theta)
        self.y += d_c * math.sin(self.theta)
        self.theta = math.atan2(math.sin(theta_new), math.cos(theta_new))

    def _ensure_w(self, v: float, w: float) -> tuple[float, float]:
        R, L = self.spec.wheel_radius, self.spec.wheel_base_length
        vmax, vmin = self.spec.max_vel, self.spec.min_vel
        if abs(v) > 0:
            v_lim = max(min(abs(v), R / 2 * (2 * vmax)), R / 2 * (2 * vmin))
            w_lim = max(min(abs(w), R / L * (vmax - vmin)), 0.0)
            r_d, l_d = uni_to_diff(R, L, v_lim, w_lim)
            hi, lo = max(r_d, l_d), min(r_d, l_d)
            if hi > vmax:
                r_d, l_d = r_d - (hi - vmax), l_d - (hi - vmax)
            elif lo < vmin:
                r_d, l_d = r_d + (vmin - lo), l_d + (vmin - lo)
            v_s, w_s = diff_to_uni(R, L, r_d, l_d)
            v, w = _sign(v) * v_s, _sign(w) * w_s
        else:
            w_min, w_max = R / L * (2 * vmin), R / L * (2 * vmax)
            w = _sign(w) * max(min(abs(w), w_max), w_min) if abs(w) > w_min else 0.0
        return uni_to_diff(R, L, v, w)

    def step(self, readings: dict) -> dict:
        self._odometry(readings["ticks"])
        x, y, th = self.x, self.y, self.theta
        c, s = math.cos(th), math.sin(th)
        u_x = u_y = 0.0
        pxs, pys = [], []
        for raw, g, (mx, my, mc, ms) in zip(readings["ir_raw"], _GAINS, self.mounts, strict=True):
            volt = raw * 3 / 1000
            d = 0.0
            for coeff in _P_INV:
                d = d * volt + coeff
            sx, sy = mx + d * mc, my + d * ms          # sensor frame -> robot frame
            px, py = x + c * sx - s * sy, y + s * sx + c * sy   # robot frame -> world frame
            pxs.append(px)
            pys.append(py)
            u_x += g * (px - x)
            u_y += g * (py - y)
        theta_ao = math.atan2(u_y, u_x)
        e = math.atan2(math.sin(theta_ao - th), math.cos(theta_ao - th))
        dt = readings["dt"]
        self.e_sum += e * dt
        w = self.kp * e + self.ki * self.e_sum + self.kd * (e - self.e_prev) / dt
        self.e_prev = e
        vel_r, vel_l = self._ensure_w(self.v, w)
        return {"vel_r": vel_r, "vel_l": vel_l, "estimate": [x, y, th], "state": "avoid_obstacles",
                "debug": {"v": self.v, "w": w, "theta_g": theta_ao, "u_ao": [u_x, u_y],
                          "ir_points_wf": [pxs, pys]}}


def _simulator(dt: float) -> Simulator:
    spec = spec_for_week(4)
    return Simulator(load_world("week4"), AvoidObstaclesBrain(spec), spec, dt=dt)


def measure(seconds: float = 60.0, repeats: int = 5, dt: float = 0.033) -> dict:
    """Best-of-`repeats` timing of `seconds` simulated seconds; step loop alone and with a Trace."""
    n = int(round(seconds / dt))
    best_step = math.inf
    collisions = 0
    for _ in range(repeats):
        sim = _simulator(dt)
        t0 = time.perf_counter()
        for _ in range(n):
            sim.step()
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
            "runs_with_collision": collisions, "final_pose": list(sim.pose),
            "world": "week4", "brain": "reference avoid_obstacles (pure Python)"}


def main(args) -> int:
    """Entry point of `simiam bench [--json] [--seconds T]`."""
    seconds = args.seconds if getattr(args, "seconds", None) else 60.0
    if seconds <= 0:
        print("simiam bench: --seconds must be positive")
        return 2
    res = measure(seconds=seconds)
    if getattr(args, "json", False):
        print(json.dumps(res))
        return 0
    print(f"simiam bench: one QuickBot, 5 IR sensors, week-4 world, reference avoid-obstacles brain, "
          f"dt = {res['dt']} s, {res['steps']} steps x {res['repeats']} (best)")
    print(f"  {res['steps_per_second']:,.0f} steps/s  ({res['us_per_step']:.1f} us/step, "
          f"{res['real_time_factor']:,.0f}x real time)")
    print(f"  {res['with_trace_steps_per_second']:,.0f} steps/s including Trace recording")
    if res["runs_with_collision"]:
        print(f"  note: the robot collided in {res['runs_with_collision']} of {res['repeats']} runs")
    return 0
