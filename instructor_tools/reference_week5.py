"""Trusted reference brain of week 5 in plain Python, independent of the course framework and of
solutions/week5: the sp14 AOandGTG blend (u_gtg and u_ao not normalised, alpha 0.25) and the author's
switching supervisor (at_goal -> stop; unsafe -> avoid_obstacles; at_obstacle -> ao_and_gtg; else
go_to_goal), in the original's operation order, down to the bit:

- an IR point reaches the world frame as the original's matrix product computed it (OpenBLAS dgemm with
  FMA): x_w = fl(fma(-sin th, y_r, fl(cos th * x_r)) + x), likewise y_w;
- at_goal measures with Octave's scaled 2-norm (simiam.control.norm follows the same rule;
  this module spells it out again so that the two are independent).

It cross-checks the solutions on the recorded goals the golden files hold back (tests/fidelity) and is
the reference of benchmarks. Student code never runs here."""

from __future__ import annotations

import math
from fractions import Fraction

from instructor_tools.reference_brains import P_INV, PID, SENSOR_GAINS, ReferenceSupervisor
from simiam.robot.quickbot import RobotSpec

ALPHA = 0.25  # the sp14 release's blend: alpha * u_gtg + (1 - alpha) * u_ao


def fma(a: float, b: float, c: float) -> float:
    """a * b + c rounded once (math.fma exists only from Python 3.13)."""
    return float(Fraction(a) * Fraction(b) + Fraction(c))


def octave_norm(x: float, y: float) -> float:
    """Octave's norm([x; y]): scl * sqrt(sum((|v| / scl)^2)), accumulated in order."""
    scl, total = 0.0, 1.0
    for t in (abs(x), abs(y)):
        if scl == t:
            total += 1.0
        elif scl < t:
            total = total * ((scl / t) * (scl / t)) + 1.0
            scl = t
        elif t != 0:
            total += (t / scl) * (t / scl)
    return scl * math.sqrt(total)


class Week5Brain(ReferenceSupervisor):
    """The week-5 supervisor: blending (`blending=True`: ao_and_gtg until at the goal, then stop) or the
    author's switching. `initial` is the state it starts in; anything other than ao_and_gtg (the
    constructor's state) counts one switch, as the original's test 5.2 did with switch_to_state."""

    def __init__(self, spec: RobotSpec, goal: tuple[float, float], v: float = 0.15, d_stop: float = 0.05,
                 d_at_obs: float = 0.25, d_unsafe: float = 0.10, blending: bool = True,
                 initial: str | None = None, gains: tuple[float, float, float] = (4.0, 0.01, 0.01),
                 **kw) -> None:
        super().__init__(spec, **kw)
        self.goal = goal
        self.v, self.d_stop, self.d_at_obs, self.d_unsafe = v, d_stop, d_at_obs, d_unsafe
        self.blending = blending
        self.pids = {name: PID(*gains) for name in ("go_to_goal", "avoid_obstacles", "ao_and_gtg")}
        self.state = "ao_and_gtg"
        self.switch_count = 0
        self.mounts = [(mx, my, math.cos(mt), math.sin(mt)) for mx, my, mt in spec.ir_mounts]
        if initial is not None:
            self.switch_to(initial)

    def switch_to(self, state: str) -> None:
        """Switch (resetting the new controller's memory and counting) unless already there."""
        if state == self.state:
            return
        self.state = state
        if state in self.pids:
            pid = self.pids[state]
            pid.E_k = pid.e_k_1 = 0.0
        self.switch_count += 1

    def distances(self, ir_raw: list[int]) -> list[float]:
        """The course's get_ir_distances: np.polyval(P_INV, raw * 3 / 1000) by Horner's rule."""
        out = []
        for raw in ir_raw:
            volt = raw * 3 / 1000
            d = 0.0
            for coeff in P_INV:
                d = d * volt + coeff
            out.append(d)
        return out

    def u_ao(self, distances: list[float]) -> tuple[float, float, list[float], list[float]]:
        """The weighted sum of the vectors from the estimate to the IR points, and the points."""
        x, y, th = self.x, self.y, self.theta
        c, s = math.cos(th), math.sin(th)
        u_x = u_y = 0.0
        pxs, pys = [], []
        for d, g, (mx, my, mc, ms) in zip(distances, SENSOR_GAINS, self.mounts, strict=True):
            sx, sy = mc * d + mx, ms * d + my                      # sensor frame -> robot frame
            px = fma(-s, sy, c * sx) + x                           # robot frame -> world frame (dgemm)
            py = fma(c, sy, s * sx) + y
            pxs.append(px)
            pys.append(py)
            u_x += (px - x) * g
            u_y += (py - y) * g
        return u_x, u_y, pxs, pys

    def choose_state(self, distances: list[float]) -> None:
        at_goal = octave_norm(self.x - self.goal[0], self.y - self.goal[1]) < self.d_stop
        if self.blending:
            self.switch_to("stop" if at_goal else "ao_and_gtg")
        elif at_goal:
            self.switch_to("stop")
        elif any(d < self.d_unsafe for d in distances):
            self.switch_to("avoid_obstacles")
        elif any(d < self.d_at_obs for d in distances):
            self.switch_to("ao_and_gtg")
        else:
            self.switch_to("go_to_goal")

    def step(self, readings: dict) -> dict:
        self.update_odometry(readings["ticks"])
        distances = self.distances(readings["ir_raw"])
        self.choose_state(distances)
        debug: dict = {"v": 0.0, "w": 0.0, "theta_g": None}
        if self.state == "stop":
            v, w = 0.0, 0.0
        else:
            g_x, g_y = self.goal[0] - self.x, self.goal[1] - self.y
            a_x, a_y, pxs, pys = self.u_ao(distances)
            if self.state == "go_to_goal":
                u = (g_x, g_y)
            elif self.state == "avoid_obstacles":
                u = (a_x, a_y)
            else:
                u = (ALPHA * g_x + (1 - ALPHA) * a_x, ALPHA * g_y + (1 - ALPHA) * a_y)
            heading = math.atan2(u[1], u[0])
            v, w = self.v, self.pids[self.state](heading, self.theta, readings["dt"])
            debug = {"v": v, "w": w, "theta_g": heading, "u_ao": [a_x, a_y], "ir_points_wf": [pxs, pys]}
        vel_r, vel_l = self.ensure_w(v, w)
        return {"vel_r": vel_r, "vel_l": vel_l, "estimate": [self.x, self.y, self.theta], "state": self.state,
                "debug": debug}
