"""Week-7 reference brain in plain Python, independent of the course framework and of solutions/week7: the
course author's navigation automaton (230acb3: at_goal -> stop; unsafe -> avoid_obstacles; progress in
go_to_goal/ao_and_gtg; no progress at an obstacle -> follow_wall on the side the IR sums say; leave the
wall when progress_made and not sliding on that side; avoid_obstacles back to the wall or the goal), with
SlidingMode's u_fw a POINT as the original stores it and sigma = [u_gtg u_ao] \\ u_fw solved as the
recorded runs did (LU with partial pivoting, the multiplier through the reciprocal pivot, no FMA).

It builds on the week-5 and week-6 reference brains (the IR points and u_ao, the wall's sensors and
vectors), so the three weeks' references share one rounding. The fidelity tests run it against the
recordings and against solutions/week7 on the hidden variants. Student code never runs here.
"""

from __future__ import annotations

import math

from instructor_tools.reference_brains import PID
from instructor_tools.reference_week5 import ALPHA, Week5Brain, octave_norm
from instructor_tools.reference_week6 import FW_GAINS, wall_sensors, wall_vectors
from simiam.robot.quickbot import RobotSpec


def solve_2x2(a11: float, a12: float, a21: float, a22: float, b1: float, b2: float) -> tuple[float, float]:
    """[a11 a12; a21 a22] x = b as the original's backslash (LAPACK dgesv, no FMA) computed it. A singular
    matrix gives the least-squares x of least length, as Octave did (u_gtg = 0: x = (0, a.b / |a|^2))."""
    if a11 == a21 == 0.0:  # the first column is zero: x_1 is free, take 0
        n = a12 * a12 + a22 * a22
        return (0.0, (a12 * b1 + a22 * b2) / n if n else 0.0)
    if abs(a21) > abs(a11):
        a11, a12, a21, a22, b1, b2 = a21, a22, a11, a12, b2, b1
    multiplier = a21 * (1.0 / a11)
    u22 = a22 - multiplier * a12
    if u22 == 0.0:  # the columns are parallel: a12 = k a11; least length on x_1 + k x_2 = c
        k = a12 / a11
        c = (a11 * b1 + a21 * b2) / (a11 * a11 + a21 * a21)
        return (c / (1 + k * k), k * c / (1 + k * k))
    x2 = (b2 - multiplier * b1) / u22
    return ((b1 - a12 * x2) / a11, x2)


class Week7Brain(Week5Brain):
    """The author's week-7 supervisor (v 0.15, d_stop 0.05, d_at_obs 0.12, d_unsafe 0.08, d_fw 0.18,
    d_prog from 10, fw_direction "left"), starting in go_to_goal."""

    def __init__(self, spec: RobotSpec, goal: tuple[float, float], v: float = 0.15, d_stop: float = 0.05,
                 d_at_obs: float = 0.12, d_unsafe: float = 0.08, d_fw: float = 0.18, **kw) -> None:
        super().__init__(spec, goal, v=v, d_stop=d_stop, d_at_obs=d_at_obs, d_unsafe=d_unsafe,
                         blending=False, **kw)
        self.pids["follow_wall"] = PID(*FW_GAINS)
        self.state = "go_to_goal"  # the constructor's state: not a switch
        self.d_fw = d_fw
        self.d_prog = 10.0
        self.fw_direction = "left"
        self.sigma: dict[str, tuple[float, float]] = {}

    # -- events ---------------------------------------------------------------------------------
    def progress_made(self) -> bool:
        return octave_norm(self.goal[0] - self.x, self.goal[1] - self.y) <= self.d_prog

    def set_progress_point(self) -> None:
        self.d_prog = min(octave_norm(self.x - self.goal[0], self.y - self.goal[1]), self.d_prog)

    def sliding(self, direction: str, distances: list[float]) -> bool:
        """SlidingMode for `direction`, then sigma; sliding when both entries are positive."""
        g = (self.goal[0] - self.x, self.goal[1] - self.y)
        a_x, a_y, pxs, pys = self.u_ao(distances)
        i_1, i_2 = wall_sensors(distances, direction)
        theta_fw = math.atan2(pys[i_2] - pys[i_1], pxs[i_2] - pxs[i_1])
        u_fw = (self.x + math.cos(theta_fw), self.y + math.sin(theta_fw))  # a point, as the original
        sigma = solve_2x2(g[0], a_x, g[1], a_y, u_fw[0], u_fw[1])
        self.sigma[direction] = sigma
        return sigma[0] > 0 and sigma[1] > 0

    # -- the automaton ----------------------------------------------------------------------------
    def choose_state(self, distances: list[float]) -> None:
        self.sigma = {}
        at_goal = octave_norm(self.x - self.goal[0], self.y - self.goal[1]) < self.d_stop
        at_obstacle = any(d < self.d_at_obs for d in distances)
        if at_goal:
            self.switch_to("stop")
        elif any(d < self.d_unsafe for d in distances):
            self.switch_to("avoid_obstacles")
        elif self.state in ("go_to_goal", "ao_and_gtg"):
            if self.progress_made():
                self.set_progress_point()
                self.switch_to("ao_and_gtg" if at_obstacle else "go_to_goal")
                self.fw_direction = ""
            elif at_obstacle:
                self.fw_direction = "left" if sum(distances[0:3]) < sum(distances[2:5]) else "right"
                self.switch_to("follow_wall")
        elif self.state == "follow_wall" and self.fw_direction in ("left", "right"):
            if self.progress_made() and not self.sliding(self.fw_direction, distances):
                self.switch_to("go_to_goal")
        elif self.state == "avoid_obstacles":
            if self.fw_direction in ("left", "right"):
                self.switch_to("follow_wall")
            else:
                self.switch_to("ao_and_gtg" if at_obstacle else "go_to_goal")

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
            elif self.state == "ao_and_gtg":
                u = (ALPHA * g_x + (1 - ALPHA) * a_x, ALPHA * g_y + (1 - ALPHA) * a_y)
            else:
                i_1, i_2 = wall_sensors(distances, self.fw_direction)
                wall = wall_vectors((pxs[i_1], pys[i_1]), (pxs[i_2], pys[i_2]), self.x, self.y, self.d_fw)
                u = wall["u_fw"]
            heading = math.atan2(u[1], u[0])
            v, w = self.v, self.pids[self.state](heading, self.theta, readings["dt"])
            debug = {"v": v, "w": w, "theta_g": heading, "u_ao": [a_x, a_y], "ir_points_wf": [pxs, pys]}
        vel_r, vel_l = self.ensure_w(v, w)
        return {"vel_r": vel_r, "vel_l": vel_l, "estimate": [self.x, self.y, self.theta], "state": self.state,
                "debug": debug}
