"""Trusted reference brains in plain Python, independent of the course framework: the original's
odometry, `ensure_w` (weeks 3 and 4), GoToGoal and AvoidObstacles, in the original's operation order.
They drive `simiam bench` and cross-check the simulator's step loop against the recorded closed-loop
runs (tests/simulator/test_sim_reference_brains.py). Student code never runs here."""

from __future__ import annotations

import math

from instructor_tools.reference_maths import uni_to_diff
from simiam.robot.dynamics import diff_to_uni
from simiam.robot.quickbot import RobotSpec

# polyfit(table_V, table_d, 5) rounded to 4 decimals: the course's get_ir_distances from week 3
P_INV = (-0.0182, 0.1690, -0.6264, 1.1853, -1.2104, 0.6293)
SENSOR_GAINS = (1.0, 1.0, 0.5, 1.0, 1.0)


def _sign(x: float) -> float:
    return float((x > 0) - (x < 0))


def _wrap(a: float) -> float:
    return math.atan2(math.sin(a), math.cos(a))


class ReferenceSupervisor:
    """Odometry, ensure_w and the wheel command shared by the reference brains.

    `ensure` is "week4" (the provided dead-zone version) or "week3" (the reference solution of the week-3
    stub, then `limit_speeds` by the simulator). `odometry_last` reproduces the week-3 tree, which updates
    the estimate after the controller."""

    def __init__(self, spec: RobotSpec, start: tuple[float, float, float] = (0.0, 0.0, 0.0),
                 ensure: str = "week4", odometry_last: bool = False) -> None:
        self.spec = spec
        self.R, self.L = spec.wheel_radius, spec.wheel_base_length
        self.x, self.y, self.theta = start
        self.prev_ticks = (0, 0)
        self.ensure = ensure
        self.odometry_last = odometry_last
        self.m_per_tick = (2 * math.pi * self.R) / spec.ticks_per_rev
        self.v_max_w0, _ = diff_to_uni(self.R, self.L, spec.max_vel, spec.max_vel)
        _, self.w_max_v0 = diff_to_uni(self.R, self.L, spec.max_vel, -spec.max_vel)

    def update_odometry(self, ticks: list[int]) -> None:
        d_r = (ticks[0] - self.prev_ticks[0]) * self.m_per_tick
        d_l = (ticks[1] - self.prev_ticks[1]) * self.m_per_tick
        self.prev_ticks = (ticks[0], ticks[1])
        d_c = (d_r + d_l) / 2
        phi = (d_r - d_l) / self.L
        theta_new = self.theta + phi
        self.x = self.x + d_c * math.cos(self.theta)
        self.y = self.y + d_c * math.sin(self.theta)
        self.theta = math.atan2(math.sin(theta_new), math.cos(theta_new))

    def ensure_w(self, v: float, w: float) -> tuple[float, float]:
        if self.ensure == "week3":
            return self._ensure_w_week3(v, w)
        return self._ensure_w_week4(v, w)

    def _ensure_w_week3(self, v: float, w: float) -> tuple[float, float]:
        vel_max = self.spec.max_vel
        w = max(min(w, self.w_max_v0), -self.w_max_v0)
        v = max(min(v, self.v_max_w0), -self.v_max_w0)
        vel_r_d, vel_l_d = uni_to_diff(self.R, self.L, v, w)
        vel_rl_max = max(vel_r_d, vel_l_d)
        vel_rl_min = min(vel_r_d, vel_l_d)
        if vel_rl_max > vel_max:
            return vel_r_d - (vel_rl_max - vel_max), vel_l_d - (vel_rl_max - vel_max)
        if vel_rl_min < -vel_max:
            return vel_r_d + (-vel_max - vel_rl_min), vel_l_d + (-vel_max - vel_rl_min)
        return vel_r_d, vel_l_d

    def _ensure_w_week4(self, v: float, w: float) -> tuple[float, float]:
        R, L = self.R, self.L
        vel_max, vel_min = self.spec.max_vel, self.spec.min_vel
        if abs(v) > 0:
            v_lim = max(min(abs(v), (R / 2) * (2 * vel_max)), (R / 2) * (2 * vel_min))
            w_lim = max(min(abs(w), (R / L) * (vel_max - vel_min)), 0)
            vel_r_d, vel_l_d = uni_to_diff(R, L, v_lim, w_lim)
            vel_rl_max = max(vel_r_d, vel_l_d)
            vel_rl_min = min(vel_r_d, vel_l_d)
            if vel_rl_max > vel_max:
                vel_r = vel_r_d - (vel_rl_max - vel_max)
                vel_l = vel_l_d - (vel_rl_max - vel_max)
            elif vel_rl_min < vel_min:
                vel_r = vel_r_d + (vel_min - vel_rl_min)
                vel_l = vel_l_d + (vel_min - vel_rl_min)
            else:
                vel_r, vel_l = vel_r_d, vel_l_d
            v_shift, w_shift = diff_to_uni(R, L, vel_r, vel_l)
            v = _sign(v) * v_shift
            w = _sign(w) * w_shift
        else:
            w_min = R / L * (2 * vel_min)
            w_max = R / L * (2 * vel_max)
            if abs(w) > w_min:
                w = _sign(w) * max(min(abs(w), w_max), w_min)
            else:
                w = 0.0
        return uni_to_diff(R, L, v, w)


class PID:
    """The course's heading PID: e wrapped, E += e*dt, derivative (e - e_prev)/dt (first-call kick)."""

    def __init__(self, kp: float, ki: float, kd: float) -> None:
        self.kp, self.ki, self.kd = kp, ki, kd
        self.E_k = 0.0
        self.e_k_1 = 0.0

    def __call__(self, reference: float, theta: float, dt: float) -> float:
        e_k = reference - theta
        e_k = math.atan2(math.sin(e_k), math.cos(e_k))
        e_P = e_k
        e_I = self.E_k + e_k * dt
        e_D = (e_k - self.e_k_1) / dt
        w = self.kp * e_P + self.ki * e_I + self.kd * e_D
        self.E_k = e_I
        self.e_k_1 = e_k
        return w


class GoToGoalBrain(ReferenceSupervisor):
    """Go to `goal` at speed v; stop when the estimate is within d_stop (at_goal uses the estimate)."""

    def __init__(self, spec: RobotSpec, goal: tuple[float, float], v: float = 0.2, d_stop: float = 0.05,
                 gains: tuple[float, float, float] = (4.0, 0.01, 0.01), **kw) -> None:
        super().__init__(spec, **kw)
        self.goal = goal
        self.v = v
        self.d_stop = d_stop
        self.pid = PID(*gains)
        self.state = "go_to_goal"

    def step(self, readings: dict) -> dict:
        if not self.odometry_last:
            self.update_odometry(readings["ticks"])
        x_g, y_g = self.goal
        if math.sqrt((self.x - x_g) ** 2 + (self.y - y_g) ** 2) < self.d_stop:
            self.state = "stop"
        theta_g = w = None
        if self.state == "stop":
            v, w_cmd = 0.0, 0.0
        else:
            theta_g = math.atan2(y_g - self.y, x_g - self.x)
            w = self.pid(theta_g, self.theta, readings["dt"])
            v, w_cmd = self.v, w
        vel_r, vel_l = self.ensure_w(v, w_cmd)
        if self.odometry_last:
            self.update_odometry(readings["ticks"])
        return {"vel_r": vel_r, "vel_l": vel_l, "estimate": [self.x, self.y, self.theta], "state": self.state,
                "debug": {"v": v, "w": w, "theta_g": theta_g}}


class AvoidObstaclesBrain(ReferenceSupervisor):
    """Week-4 avoid-obstacles: the five IR points in the world frame (by the estimate), u_ao = sum of
    gain * (p_i - position), PID on atan2(u_ao)."""

    def __init__(self, spec: RobotSpec, v: float = 0.1, gains: tuple[float, float, float] = (5.0, 0.01, 0.01),
                 **kw) -> None:
        super().__init__(spec, **kw)
        self.v = v
        self.pid = PID(*gains)
        self.mounts = [(mx, my, math.cos(mt), math.sin(mt)) for mx, my, mt in spec.ir_mounts]

    def step(self, readings: dict) -> dict:
        self.update_odometry(readings["ticks"])
        x, y, th = self.x, self.y, self.theta
        c, s = math.cos(th), math.sin(th)
        u_x = u_y = 0.0
        pxs, pys = [], []
        for raw, g, (mx, my, mc, ms) in zip(readings["ir_raw"], SENSOR_GAINS, self.mounts, strict=True):
            volt = raw * 3 / 1000
            d = 0.0
            for coeff in P_INV:
                d = d * volt + coeff
            sx, sy = mx + d * mc, my + d * ms                   # sensor frame -> robot frame
            px, py = x + c * sx - s * sy, y + s * sx + c * sy   # robot frame -> world frame
            pxs.append(px)
            pys.append(py)
            u_x += g * (px - x)
            u_y += g * (py - y)
        theta_ao = math.atan2(u_y, u_x)
        w = self.pid(theta_ao, th, readings["dt"])
        vel_r, vel_l = self.ensure_w(self.v, w)
        return {"vel_r": vel_r, "vel_l": vel_l, "estimate": [x, y, th], "state": "avoid_obstacles",
                "debug": {"v": self.v, "w": w, "theta_g": theta_ao, "u_ao": [u_x, u_y],
                          "ir_points_wf": [pxs, pys]}}
