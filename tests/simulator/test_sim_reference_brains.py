"""The step loop against the recorded closed-loop GoToGoal runs, driven by the trusted reference brain
(instructor_tools.reference_brains, not the course code): true poses <= 1e-6 m over the whole run,
ticks exact, wheel speeds exact. Every goal present in the files is run."""

from __future__ import annotations

import csv

import pytest
from sim_helpers import DATA, wrong

from instructor_tools.reference_brains import GoToGoalBrain
from simiam.course.weeks import spec_for_week
from simiam.simulator import Simulator
from simiam.world import load_world

RUNS = {
    # file: (week, dt, brain options) as described in tests/data/golden/README (../shared/golden/README.md)
    "gotogoal_closed_loop.csv": (4, 0.033, {}),
    "gotogoal_closed_loop_dt0.05.csv": (4, 0.05, {}),
    "gotogoal_closed_loop_week3.csv": (3, 0.033, {"gains": (5.0, 0.01, 0.01), "ensure": "week3",
                                                  "odometry_last": True}),
}


def replay(sim_cls, name: str) -> dict:
    week, dt, options = RUNS[name]
    with (DATA / "golden" / name).open(newline="") as f:
        goals: dict[str, list[dict]] = {}
        for r in csv.DictReader(f):
            goals.setdefault(r["goal_id"], []).append(r)
    worst, bad = 0.0, []
    for gid, rs in goals.items():
        spec = spec_for_week(week)
        brain = GoToGoalBrain(spec, (float(rs[0]["x_g"]), float(rs[0]["y_g"])), v=0.2, d_stop=0.05, **options)
        sim = sim_cls(load_world("week3"), brain, spec, dt=dt)
        rec = sim.last
        for r in sorted(rs, key=lambda r: int(r["step"])):
            while sim.steps_taken < int(r["step"]):
                rec = sim.step()
            want = (float(r["x"]), float(r["y"]), float(r["theta"]))
            worst = max(worst, *(abs(a - b) for a, b in zip(rec.pose, want, strict=True)))
            if rec.ticks != (int(r["right_ticks"]), int(r["left_ticks"])):
                bad.append((gid, r["step"], "ticks"))
            if rec.step > 0 and (rec.vel_r, rec.vel_l) != (float(r["vel_r"]), float(r["vel_l"])):
                bad.append((gid, r["step"], "wheel speeds"))
            if rec.step > 0 and rec.command["state"] != r["state"]:
                bad.append((gid, r["step"], "state"))
    return {"goals": len(goals), "max_pose_error": worst, "bad": bad}


@pytest.mark.parametrize("name", sorted(RUNS))
def test_closed_loop_recordings_reproduce(name):
    res = replay(Simulator, name)
    assert res["goals"] > 0
    assert res["max_pose_error"] <= 1e-6, res
    assert res["bad"] == [], res["bad"][:5]


def test_replay_catches_a_loop_without_the_one_step_delay():
    res = replay(wrong("simulator_wrong_order").NoDelaySimulator, "gotogoal_closed_loop.csv")
    assert res["max_pose_error"] > 1e-6 or res["bad"]


def ensure_w_mismatches(limit_after_week3: bool = True) -> tuple[int, int]:
    """The reference brains' ensure_w against ensure_w.csv (every version and row): (rows, mismatches)."""
    import dataclasses

    from instructor_tools.reference_brains import ReferenceSupervisor
    from simiam.robot.quickbot import limit_speeds

    with (DATA / "golden" / "ensure_w.csv").open(newline="") as f:
        rows = list(csv.DictReader(f))
    bad = 0
    for r in rows:
        week4 = r["version"] == "week4"
        spec = dataclasses.replace(spec_for_week(4 if week4 else 3), max_vel=float(r["vel_max"]),
                                   min_vel=float(r["vel_min"]))
        vel_r, vel_l = ReferenceSupervisor(spec, ensure="week4" if week4 else "week3").ensure_w(
            float(r["v"]), float(r["w"]))
        if not week4 and limit_after_week3:  # the week-3 code calls limit_speeds inside ensure_w
            vel_r, vel_l = limit_speeds(vel_r, vel_l, spec.max_vel, spec.min_vel)
        bad += (vel_r, vel_l) != (float(r["vel_r"]), float(r["vel_l"]))
    return len(rows), bad


def test_reference_ensure_w_is_bit_exact():
    rows, bad = ensure_w_mismatches()
    assert rows > 0 and bad == 0


def test_ensure_w_check_catches_a_missing_limit():
    assert ensure_w_mismatches(limit_after_week3=False)[1] > 0
