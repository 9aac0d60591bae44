"""Synthetic Seam-2 traces for the viewer and report tests (no simulator needed).

A unicycle with Euler steps, a P heading regulator, a centre-line IR ray cast and a drifting odometry
estimate. The numbers are plausible, not faithful: these traces only exercise the page and the report.
Run `python tests/data/traces/synthetic.py` to rewrite the committed samples next to this file.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from shapely.geometry import LineString, Point, Polygon

HERE = Path(__file__).resolve().parent
BASE_PLATE = [(0.0335, 0.0534), (0.0429, 0.0534), (0.0639, 0.0334), (0.0686, 0.0), (0.0639, -0.0334),
              (0.0429, -0.0534), (0.0335, -0.0534), (-0.0465, -0.0534), (-0.0815, -0.0534),
              (-0.1112, -0.0387), (-0.1112, 0.0387), (-0.0815, 0.0534), (-0.0465, 0.0534)]
IR_MOUNTS = [(-0.0474, 0.0534, math.pi / 2), (0.0613, 0.0244, math.pi / 4), (0.0636, 0.0, 0.0),
             (0.0461, -0.0396, -math.pi / 4), (-0.0690, -0.0534, -math.pi / 2)]
WALLS = [[[-1.6, -1.5], [1.4, -1.5], [1.4, -1.4], [-1.6, -1.4]],
         [[-1.5, -1.4], [-1.5, 1.6], [-1.6, 1.6], [-1.6, -1.4]],
         [[1.5, -1.5], [1.5, 1.5], [1.4, 1.5], [1.4, -1.5]],
         [[-1.5, 1.5], [1.5, 1.5], [1.5, 1.6], [-1.5, 1.6]]]
L_SHAPE = [[0.4, -0.2], [0.6, -0.2], [0.6, 0.6], [0.0, 0.6], [0.0, 0.4], [0.4, 0.4]]
R, L_BASE = 0.0325, 0.09925
M_PER_TICK = 2 * math.pi * R / 16


def _to_world(px: float, py: float, x: float, y: float, th: float) -> tuple[float, float]:
    c, s = math.cos(th), math.sin(th)
    return (x + c * px - s * py, y + s * px + c * py)


def _ir_range(obstacles: list[Polygon], x: float, y: float, th: float, mount) -> float:
    sx, sy = _to_world(mount[0], mount[1], x, y, th)
    a = th + mount[2]
    ray = LineString([(sx, sy), (sx + 0.3 * math.cos(a), sy + 0.3 * math.sin(a))])
    best = 0.3
    for ob in obstacles:
        hit = ray.intersection(ob.exterior)
        if not hit.is_empty:
            best = min(best, Point(sx, sy).distance(hit))
    return min(max(best, 0.04), 0.3)


def _raw(d: float) -> int:
    volts = 0.4 + 2.35 * (0.3 - d) / 0.26  # a straight line through the table's ends: synthetic only
    return int(math.floor(1000 * volts / 3 + 0.5))


def _wrap(a: float) -> float:
    return math.atan2(math.sin(a), math.cos(a))


def make_trace(week: int = 3, seconds: float = 15.0, dt: float = 0.033, goal=(1.0, 1.0),
               v: float = 0.15, stop_on_collision: bool = True) -> dict:
    """Return a Seam-2 trace dict; week 4 adds the L obstacle, IR points and u_ao, and wanders."""
    obstacles_xy = WALLS + ([L_SHAPE] if week == 4 else [])
    obstacles = [Polygon(p) for p in obstacles_xy]
    cols = {k: [] for k in ("t", "x", "y", "theta", "x_est", "y_est", "theta_est", "ticks_r", "ticks_l",
                            "vel_r", "vel_l", "ir_raw", "ir_range", "theta_g", "u_ao", "ir_points_wf",
                            "v", "w", "state", "collided")}
    x = y = th = 0.0
    xe = ye = the = 0.0
    ang_r = ang_l = 0.0
    vel_r = vel_l = 0.0
    collision = None
    n = int(round(seconds / dt))
    gains = [1.0, 0.5, 1.0, 0.5, 1.0]
    for k in range(n + 1):
        t = k * dt
        if k > 0:  # move with last step's wheel speeds
            vv, ww = R * (vel_r + vel_l) / 2, R * (vel_r - vel_l) / L_BASE
            x += vv * math.cos(th) * dt
            y += vv * math.sin(th) * dt
            th = _wrap(th + ww * dt)
            ang_r += vel_r * dt
            ang_l += vel_l * dt
            # odometry that drifts: a 3 % scale error on the left wheel
            xe += vv * 0.99 * math.cos(the) * dt
            ye += vv * 0.99 * math.sin(the) * dt
            the = _wrap(the + ww * 1.03 * dt)
        body = Polygon([_to_world(px, py, x, y, th) for px, py in BASE_PLATE])
        hit = k > 0 and any(body.intersects(o) for o in obstacles)
        ranges = [_ir_range(obstacles, x, y, th, m) for m in IR_MOUNTS]
        theta_g = u_ao = pts = None
        state = "go_to_goal"
        if week == 4:
            state = "avoid_obstacles"
            pts_x, pts_y = [], []
            for d, m in zip(ranges, IR_MOUNTS, strict=True):
                px, py = _to_world(m[0] + d * math.cos(m[2]), m[1] + d * math.sin(m[2]), xe, ye, the)
                pts_x.append(px)
                pts_y.append(py)
            pts = [pts_x, pts_y]
            u_ao = [sum(g * (px - xe) for g, px in zip(gains, pts_x, strict=True)),
                    sum(g * (py - ye) for g, py in zip(gains, pts_y, strict=True))]
            heading = math.atan2(u_ao[1], u_ao[0])
        else:
            theta_g = math.atan2(goal[1] - ye, goal[0] - xe)
            heading = theta_g
        w_cmd = 4.0 * _wrap(heading - the)
        near = week != 4 and math.hypot(goal[0] - xe, goal[1] - ye) < 0.05
        v_cmd = 0.0 if near else v
        if near:
            state, w_cmd = "stop", 0.0
        vel_r = max(-8.3776, min(8.3776, (2 * v_cmd + w_cmd * L_BASE) / (2 * R)))
        vel_l = max(-8.3776, min(8.3776, (2 * v_cmd - w_cmd * L_BASE) / (2 * R)))
        if hit:
            vel_r = vel_l = 0.0
        row = {"t": t, "x": x, "y": y, "theta": th, "x_est": xe, "y_est": ye, "theta_est": the,
               "ticks_r": int(math.floor(ang_r * R / M_PER_TICK + 0.5)),
               "ticks_l": int(math.floor(ang_l * R / M_PER_TICK + 0.5)),
               "vel_r": vel_r, "vel_l": vel_l, "ir_raw": [_raw(d) for d in ranges], "ir_range": ranges,
               "theta_g": theta_g, "u_ao": u_ao, "ir_points_wf": pts, "v": v_cmd, "w": w_cmd,
               "state": state, "collided": bool(hit)}
        for key, val in row.items():
            cols[key].append(val)
        if hit and collision is None:
            collision = {"step": k, "t": t, "pose": [x, y, th]}
            if stop_on_collision:
                break
    return {"format": "simiam-trace/1", "week": week, "dt": dt, "seconds": seconds,
            "world": {"name": f"week{week}-synthetic", "obstacles": obstacles_xy},
            "robot": {"base_plate": [list(p) for p in BASE_PLATE], "ir_mounts": [list(m) for m in IR_MOUNTS],
                      "ir_min_range": 0.04, "ir_max_range": 0.3, "ir_spread": math.radians(6),
                      "wheel_radius": R, "wheel_base_length": L_BASE},
            "start": [0.0, 0.0, 0.0], "goal": None if week == 4 else list(goal),
            "steps": cols, "collision": collision,
            "meta": {"submission": "synthetic", "seed": 1234}}


SAMPLES = {
    "week3_goal.json": dict(week=3, seconds=12.0, goal=(1.0, 1.0)),
    "week3_crash.json": dict(week=3, seconds=15.0, goal=(2.0, -0.3), v=0.2),
    "week4_wander.json": dict(week=4, seconds=20.0, v=0.12),
}


def load(name: str) -> dict:
    """One committed sample trace by file name."""
    return json.loads((HERE / name).read_text())


def _rounded(v, digits: int = 6):
    """Round every float so that the committed samples stay small."""
    if isinstance(v, float):
        return round(v, digits)
    if isinstance(v, list):
        return [_rounded(x, digits) for x in v]
    if isinstance(v, dict):
        return {k: _rounded(x, digits) for k, x in v.items()}
    return v


if __name__ == "__main__":
    for fname, kwargs in SAMPLES.items():
        tr = _rounded(make_trace(**kwargs))
        (HERE / fname).write_text(json.dumps(tr, separators=(",", ":")))
        print(fname, len(tr["steps"]["t"]), "rows, collision:", tr["collision"])
