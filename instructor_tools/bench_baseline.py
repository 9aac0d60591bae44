"""The baseline `simiam bench` prints next to the simulator: one flat Python loop doing a step's arithmetic.

It computes inline what the reference avoid-obstacles brain does (odometry, uni_to_diff, the IR points,
ensure_w): the answers of weeks 2-4, so it lives here with the other instructor tooling, never in the wheel.
"""

from __future__ import annotations

import math

from simiam.course.weeks import spec_for_week
from simiam.robot.ir_sensor import VOLTAGE_COEFFS, mounted_cone


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
