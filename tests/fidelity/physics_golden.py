"""Golden-trace checks for the trusted physics, written as functions of the implementation under test,
so that the same check runs on simiam's code and on the deliberately wrong versions in
tests/data/wrong_physics/ (each must be caught). Every row and case present in the CSVs is used."""

from __future__ import annotations

import csv
import importlib.util
import math
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

DATA = Path(__file__).resolve().parents[1] / "data"
GOLDEN = DATA / "golden"


def rows(name: str) -> list[dict[str, str]]:
    with (GOLDEN / name).open(newline="") as f:
        return list(csv.DictReader(f))


def grouped(name: str, key: str) -> dict[str, list[dict[str, str]]]:
    out: dict[str, list[dict[str, str]]] = {}
    for r in rows(name):
        out.setdefault(r[key], []).append(r)
    return out


def wrong(name: str) -> ModuleType:
    """Load a wrong implementation kept as test data."""
    path = DATA / "wrong_physics" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"wrong_physics_{name}", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def check_drive(move: Callable, encoder_cls: type, limit: Callable, R: float, L: float) -> dict:
    """Replay drive_open_loop.csv: limited speeds, then `move` and the encoders once per row.
    Returns the worst pose error, tick mismatches, applied-speed mismatches and the case count."""
    worst = 0.0
    ticks_bad: list[tuple] = []
    applied_bad: list[tuple] = []
    dt = 0.033
    cases = grouped("drive_open_loop.csv", "case_id")
    for cid, rs in cases.items():
        rs.sort(key=lambda r: int(r["step"]))
        vr, vl = limit(float(rs[0]["vel_r_cmd"]), float(rs[0]["vel_l_cmd"]))
        if (vr, vl) != (float(rs[0]["vel_r_applied"]), float(rs[0]["vel_l_applied"])):
            applied_bad.append((cid, vr, vl))
        x = y = th = 0.0
        enc_r, enc_l = encoder_cls(16), encoder_cls(16)
        step = 0
        for r in rs:
            while step < int(r["step"]):
                x, y, th = move(x, y, th, vr, vl, R, L, dt)
                enc_r.update(vr, dt)
                enc_l.update(vl, dt)
                step += 1
            worst = max(worst, abs(x - float(r["x"])), abs(y - float(r["y"])), abs(th - float(r["theta"])))
            if (enc_r.ticks, enc_l.ticks) != (int(r["right_ticks"]), int(r["left_ticks"])):
                ticks_bad.append((cid, step))
    return {"max_pose_error": worst, "ticks_bad": ticks_bad, "applied_bad": applied_bad, "cases": len(cases)}


def check_ir(ranger: Callable) -> dict:
    """Replay ir_readings.csv. `ranger(pose)` returns (ranges[5], raws[5], apexes[5]) for the robot placed
    at pose in the final world. Raw values must match exactly; distances and apexes are compared."""
    worst_d = 0.0
    worst_apex = 0.0
    raw_bad: list[tuple] = []
    poses = grouped("ir_readings.csv", "pose_id")
    for pid, rs in poses.items():
        pose = (float(rs[0]["x"]), float(rs[0]["y"]), float(rs[0]["theta"]))
        ranges, raws, apexes = ranger(pose)
        for r in rs:
            i = int(r["sensor"]) - 1
            worst_d = max(worst_d, abs(ranges[i] - float(r["true_distance"])))
            if raws[i] != int(r["raw_value"]):
                raw_bad.append((pid, i + 1, raws[i], int(r["raw_value"])))
            worst_apex = max(worst_apex, math.hypot(apexes[i][0] - float(r["sensor_x"]),
                                                    apexes[i][1] - float(r["sensor_y"])))
    return {"max_distance_error": worst_d, "max_apex_error": worst_apex, "raw_bad": raw_bad,
            "poses": len(poses)}


def check_world(obstacles: list, name: str = "world_walls.csv") -> dict:
    """Compare obstacle vertices with a recorded world, world_walls.csv by default (polygon and vertex ids
    are 1-based)."""
    worst = 0.0
    exact = True
    recorded = rows(name)
    n_polys = len({r["polygon_id"] for r in recorded})
    for r in recorded:
        k, v = int(r["polygon_id"]) - 1, int(r["vertex_id"]) - 1
        px, py = float(obstacles[k][v][0]), float(obstacles[k][v][1])
        worst = max(worst, abs(px - float(r["x"])), abs(py - float(r["y"])))
        exact = exact and (px, py) == (float(r["x"]), float(r["y"]))
    return {"max_vertex_error": worst, "bit_exact": exact, "polygons": len(obstacles), "recorded": n_polys}


def check_kinematics(fn: Callable, name: str, inputs: tuple[str, str], outputs: tuple[str, str],
                     R: float, L: float) -> dict:
    """fn(R, L, a, b) -> (c, d) against uni_to_diff.csv / diff_to_uni.csv: worst error and bit-exactness."""
    worst = 0.0
    not_exact = 0
    recorded = rows(name)
    for r in recorded:
        got = fn(R, L, float(r[inputs[0]]), float(r[inputs[1]]))
        want = (float(r[outputs[0]]), float(r[outputs[1]]))
        worst = max(worst, abs(got[0] - want[0]), abs(got[1] - want[1]))
        not_exact += got != want
    return {"max_error": worst, "not_bit_exact": not_exact, "rows": len(recorded)}
