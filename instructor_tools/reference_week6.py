"""Week-6 reference brain in plain Python, independent of the course framework and of solutions/week6:
the original's FollowWall (sp14: sensor choice with MATLAB's stable sort, u_fw = d_fw*u_fw_tp + u_fw_pp,
a P regulator with Kp 2) under the week-4 supervisor (odometry first, the dead-zone ensure_w).

It rounds as the recorded runs did (tests/data/golden/README of the shared copy, "Bit-level findings"):
the IR points go to the world frame with the fused multiply-adds of the original's BLAS, and lengths are
Octave's scaled norm. The fidelity tests run it against the recordings and against solutions/week6 on the
cases that are kept back. Student code never runs here.
"""

from __future__ import annotations

import math

from instructor_tools.reference_brains import P_INV, PID, ReferenceSupervisor
from simiam.control.norm import norm
from simiam.physics.transform import transform_point
from simiam.robot.quickbot import RobotSpec

FW_GAINS = (2.0, 0.0, 0.0)


def wall_sensors(distances: list[float], direction: str) -> tuple[int, int]:
    """(i_1, i_2), the sensors (0..4) whose points become p_1 and p_2 (the original's choice).

    Left ("" too): of sensors 0, 1, 2 the two closest, ties to the lower index; p_1 the lower index.
    Right: of 4, 3, 2 the two closest, ties in that order; p_1 the higher index."""
    candidates = [4, 3, 2] if direction == "right" else [0, 1, 2]
    ranked = sorted(range(3), key=lambda k: (distances[candidates[k]], k))  # stable, spelled out
    a, b = candidates[ranked[0]], candidates[ranked[1]]
    return (max(a, b), min(a, b)) if direction == "right" else (min(a, b), max(a, b))


def wall_vectors(p_1: tuple[float, float], p_2: tuple[float, float], x: float, y: float,
                 d_fw: float) -> dict[str, tuple[float, float]]:
    """u_fw_t, u_fw_tp, u_fw_p, the unit vector toward the wall, u_fw_pp and u_fw, in the sp14 order."""
    t = (p_2[0] - p_1[0], p_2[1] - p_1[1])
    n_t = norm(t)
    tp = (t[0] / n_t, t[1] / n_t)
    a = (p_1[0] - x, p_1[1] - y)
    along = a[0] * tp[0] + a[1] * tp[1]
    p = (a[0] - along * tp[0], a[1] - along * tp[1])
    n_p = norm(p)
    unit = (p[0] / n_p, p[1] / n_p)
    pp = (p[0] - d_fw * unit[0], p[1] - d_fw * unit[1])
    fw = (d_fw * tp[0] + pp[0], d_fw * tp[1] + pp[1])
    return {"u_fw_t": t, "u_fw_tp": tp, "u_fw_p": p, "unit": unit, "u_fw_pp": pp, "u_fw": fw}


class FollowWallBrain(ReferenceSupervisor):
    """Follow the wall on `direction`'s side at d_fw with speed v, from the estimate `start`."""

    def __init__(self, spec: RobotSpec, direction: str = "left", d_fw: float = 0.18, v: float = 0.15,
                 start: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> None:
        super().__init__(spec, start=start)
        self.direction = direction
        self.d_fw = d_fw
        self.v = v
        self.pid = PID(*FW_GAINS)
        self.mounts = [(mx, my, math.cos(mt), math.sin(mt)) for mx, my, mt in spec.ir_mounts]
        self.last: dict = {}

    def ir_points(self, ir_raw: list[int]) -> tuple[list[float], list[tuple[float, float]]]:
        """The IR distances and their points in the world frame, by the estimate."""
        distances, points = [], []
        pose = (self.x, self.y, self.theta)
        for raw, (mx, my, mc, ms) in zip(ir_raw, self.mounts, strict=True):
            volt = raw * 3 / 1000
            d = 0.0
            for coeff in P_INV:
                d = d * volt + coeff
            distances.append(d)
            points.append(transform_point(pose, mc * d + mx, ms * d + my))
        return distances, points

    def step(self, readings: dict) -> dict:
        self.update_odometry(readings["ticks"])
        distances, points = self.ir_points(readings["ir_raw"])
        i_1, i_2 = wall_sensors(distances, self.direction)
        vectors = wall_vectors(points[i_1], points[i_2], self.x, self.y, self.d_fw)
        u_fw = vectors["u_fw"]
        theta_fw = math.atan2(u_fw[1], u_fw[0])
        w = self.pid(theta_fw, self.theta, readings["dt"])
        self.last = {"sensors": (i_1, i_2), "theta_fw": theta_fw, "e_k": self.pid.e_k_1, "w": w, **vectors}
        vel_r, vel_l = self.ensure_w(self.v, w)
        return {"vel_r": vel_r, "vel_l": vel_l, "estimate": [self.x, self.y, self.theta],
                "state": "follow_wall",
                "debug": {"v": self.v, "w": w, "theta_g": theta_fw,
                          "ir_points_wf": [[p[0] for p in points], [p[1] for p in points]]}}
