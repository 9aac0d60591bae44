"""Open-loop driving against drive_open_loop.csv (every case and row): poses <= 1e-9 m, ticks exact,
applied speeds exact; through the components and through the Simulator's step loop."""

from __future__ import annotations

import pytest
from physics_golden import check_drive, grouped, wrong

from simiam.course.weeks import spec_for_week
from simiam.robot.dynamics import move, move_arc
from simiam.robot.quickbot import limit_speeds
from simiam.robot.wheel_encoder import WheelEncoder
from simiam.simulator import ConstantBrain, Simulator
from simiam.world import World

SPEC = spec_for_week(4)  # the recordings are sp14: 130/30 rpm with the dead zone
R, L = SPEC.wheel_radius, SPEC.wheel_base_length


def limit(r, l):
    return limit_speeds(r, l, SPEC.max_vel, SPEC.min_vel)


@pytest.mark.parametrize("move_fn", [move, move_arc], ids=["chord", "arc"])
def test_drive_open_loop_matches(move_fn):
    res = check_drive(move_fn, WheelEncoder, limit, R, L)
    assert res["cases"] > 0
    assert res["max_pose_error"] <= 1e-9, res
    assert res["ticks_bad"] == [] and res["applied_bad"] == [], res


def test_simulator_loop_reproduces_open_loop():
    """The Simulator's own loop: step 1 applies the initial zero speeds, so golden row k = sim step k+1."""
    worst = 0.0
    for cid, rs in grouped("drive_open_loop.csv", "case_id").items():
        rs.sort(key=lambda r: int(r["step"]))
        brain = ConstantBrain(float(rs[0]["vel_r_cmd"]), float(rs[0]["vel_l_cmd"]))
        sim = Simulator(World("empty", []), brain, SPEC, dt=0.033)
        rec = sim.step()
        assert rec.pose == (0.0, 0.0, 0.0), "the first step must not move (speeds start at 0)"
        assert (rec.vel_r, rec.vel_l) == (float(rs[0]["vel_r_applied"]), float(rs[0]["vel_l_applied"]))
        by_step = {int(r["step"]): r for r in rs}
        for k in range(1, max(by_step) + 1):
            rec = sim.step()
            if k in by_step:
                r = by_step[k]
                want = (float(r["x"]), float(r["y"]), float(r["theta"]))
                worst = max(worst, *(abs(a - b) for a, b in zip(rec.pose, want, strict=True)))
                assert rec.ticks == (int(r["right_ticks"]), int(r["left_ticks"])), (cid, k)
    assert worst <= 1e-9


@pytest.mark.parametrize("mistake", [
    ("euler", lambda: (wrong("dynamics_euler").move, WheelEncoder, limit)),
    ("wrapped_theta", lambda: (wrong("dynamics_wrapped").move, WheelEncoder, limit)),
    ("encoder_no_carry", lambda: (move, wrong("encoder_no_carry").WheelEncoder, limit)),
    ("no_dead_zone", lambda: (move, WheelEncoder, lambda r, l: wrong("limits_wrong").no_dead_zone(
        r, l, SPEC.max_vel, SPEC.min_vel))),
], ids=lambda m: m[0])
def test_drive_check_catches(mistake):
    move_fn, enc, lim = mistake[1]()
    res = check_drive(move_fn, enc, lim, R, L)
    assert res["max_pose_error"] > 1e-9 or res["ticks_bad"] or res["applied_bad"]
