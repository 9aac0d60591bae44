"""Week 7 against the original's recordings: the course author's navigation automaton (230acb3) in the
final world (the trap around the start).

fsm_closed_loop_dt0.05.csv / fsm_closed_loop_dt0.033.csv: solutions/week7 as shipped (v 0.15, d_stop 0.05,
d_at_obs 0.12, d_unsafe 0.08, d_fw 0.18, d_prog from 10, fw_direction "left", starting in go_to_goal;
GoToGoal and AvoidObstacles 4/0.01/0.01, AOandGTG alpha 0.25, FollowWall 2/0/0), the week-4 robot, only the
goal set per case, as the original's test 7.1. Every recorded step must match: the true pose to 1e-6 m,
the ticks, the wheel speeds set (1e-9 rad/s: one ulp decides the dead zone, so a wrong bit shows as
3.14 rad/s), the state, the switch count, fw_direction, d_prog, the controller's (v, w) and heading, sigma
wherever a sliding test ran (and no sliding test where none ran), and the run must end as recorded (the
stop, or the crash, at the same step). A wrong step order or a wrong automaton must fail.
"""

from __future__ import annotations

import csv
import math
from collections import defaultdict
from pathlib import Path

import mistakes
import pytest
from week7_setup import WEEK7

from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests/data/golden"
FILES = ("fsm_closed_loop_dt0.05.csv", "fsm_closed_loop_dt0.033.csv")
POSE_TOL = 1e-6
TOL = 1e-9


def _cases(name: str) -> dict[str, list[dict]]:
    by_case: dict[str, list[dict]] = defaultdict(list)
    with (GOLDEN / name).open() as f:
        for row in csv.DictReader(f):
            by_case[row["case"]].append(row)
    return {k: sorted(v, key=lambda r: int(r["step"])) for k, v in by_case.items()}


CASES = [(name, case) for name in FILES for case in _cases(name)]


def _close(a, b: float, tol: float = TOL) -> bool:
    return a is not None and abs(a - b) <= tol * max(1.0, abs(b))


def _sigma_problem(sup, direction: str, row: dict) -> str | None:
    recorded = (float(row[f"sigma_{direction}_1"]), float(row[f"sigma_{direction}_2"]))
    ran = f"sliding_{direction}" in sup.event_values
    if math.isnan(recorded[0]):
        return f"sliding_{direction} ran, the original did not test it" if ran else None
    if not ran:
        return f"sliding_{direction} did not run, the original tested it"
    sigma = getattr(sup, f"sigma_{direction}")
    if not all(_close(float(s), r) for s, r in zip(sigma, recorded, strict=True)):
        return f"sigma_{direction} {[float(s) for s in sigma]}, recorded {list(recorded)}"
    return None


def step_problems(rec, sup, row: dict) -> list[str]:
    """What differs between one simulated step and its recorded row."""
    problems = []
    err = max(abs(rec.pose[0] - float(row["x"])), abs(rec.pose[1] - float(row["y"])))
    if err > POSE_TOL:
        problems.append(f"true pose off by {err:.3g} m")
    if list(rec.ticks) != [int(row["right_ticks"]), int(row["left_ticks"])]:
        problems.append(f"ticks {list(rec.ticks)}, recorded {[row['right_ticks'], row['left_ticks']]}")
    if not (_close(rec.vel_r, float(row["vel_r"])) and _close(rec.vel_l, float(row["vel_l"]))):
        problems.append(f"wheels ({rec.vel_r!r}, {rec.vel_l!r}), recorded ({row['vel_r']}, {row['vel_l']})")
    if bool(rec.collided) != (row["crashed"] == "1"):
        problems.append(f"collided {rec.collided}, recorded crashed={row['crashed']}")
    if rec.command["state"] != row["state"]:
        problems.append(f"state {rec.command['state']}, recorded {row['state']}")
    if sup.switch_count != int(row["switch_count"]):
        problems.append(f"switch_count {sup.switch_count}, recorded {row['switch_count']}")
    if sup.fw_direction != row["fw_direction"]:
        problems.append(f"fw_direction {sup.fw_direction!r}, recorded {row['fw_direction']!r}")
    if not _close(float(sup.d_prog), float(row["d_prog"]), 1e-12):
        problems.append(f"d_prog {sup.d_prog!r}, recorded {row['d_prog']}")
    debug = rec.command["debug"]
    for key, column in (("v", "ctrl_v"), ("w", "ctrl_w"), ("theta_g", "heading")):
        if not math.isnan(float(row[column])) and not _close(debug[key], float(row[column])):
            problems.append(f"controller {key} {debug[key]!r}, recorded {row[column]}")
    for direction in ("left", "right"):
        problem = _sigma_problem(sup, direction, row)
        if problem:
            problems.append(problem)
    return problems


def replay(folder: Path, name: str, case: str) -> list[str]:
    """Run one recorded case with the code in `folder`; return what differs (from the first wrong step)."""
    rows = _cases(name)[case]
    dt = float(rows[1]["t"]) / int(rows[1]["step"])
    goal = (float(rows[0]["x_g"]), float(rows[0]["y_g"]))
    sub = load_submission(folder, WEEK7)
    assert sub.ok, sub.errors
    brain = LocalBrain(sub, WEEK7, {"goal": goal})
    sup = brain.supervisor
    assert (sup.v, sup.d_prog, sup.fw_direction) == (float(rows[0]["v"]), 10, rows[0]["fw_direction"])
    sim = Simulator(load_world(WEEK7.world), brain, WEEK7.spec, dt=dt, start=(0.0, 0.0, 0.0))
    if list(sim.ir_raw) != [int(rows[0][f"ir_raw_{i}"]) for i in range(1, 6)]:
        return [f"start: IR {list(sim.ir_raw)}"]
    for row in rows[1:]:
        rec = sim.step()
        assert rec.step == int(row["step"])
        problems = step_problems(rec, sup, row)
        if problems:
            return [f"step {rec.step}: {p}" for p in problems]
    return []


@pytest.mark.parametrize(("name", "case"), CASES)
def test_solutions_reproduce_the_recorded_navigation(name, case):
    problems = replay(ROOT / "solutions/week7", name, case)
    assert not problems, f"{name} case {case}: {problems}"


def test_the_recordings_end_as_the_golden_readme_says():
    """Case 1 stops at the goal (dt 0.05: step 553 with 18 switches; dt 0.033: step 830, 20 switches) and
    case 3 crashes into the trap's bottom bar in avoid_obstacles (steps 58 and 86): the replay above covers
    every one of these rows, so a match is a match of the endings too."""
    ends = {}
    for name, case in CASES:
        rows = _cases(name)[case]
        stops = [r for r in rows if r["state"] == "stop"]
        crash = [r for r in rows if r["crashed"] == "1"]
        ends[(name, case)] = (int(stops[0]["step"]), stops[0]["switch_count"]) if stops else (
            "crash", int(crash[0]["step"]), crash[0]["state"])
    assert ends == {
        ("fsm_closed_loop_dt0.05.csv", "1"): (553, "18"),
        ("fsm_closed_loop_dt0.05.csv", "3"): ("crash", 58, "avoid_obstacles"),
        ("fsm_closed_loop_dt0.033.csv", "1"): (830, "20"),
        ("fsm_closed_loop_dt0.033.csv", "3"): ("crash", 86, "avoid_obstacles"),
    }


@pytest.mark.parametrize("mistake", ["week7_odometry_last", "week7_wall_on_far_side"])
def test_a_wrong_step_order_or_automaton_is_caught(tmp_path, mistake):
    folder = mistakes.build("submissions", mistake, tmp_path, 7)
    assert replay(folder, "fsm_closed_loop_dt0.05.csv", "1")


# What ../shared/golden/README.md states about every recorded goal, the held-back case 2 included: the step
# of the first stop (with the switch count and the true distance to the goal, m, 4 decimals) or of the crash
# (with the state it happened in).
ENDINGS = {
    0.05: {(1.1, 1.1): ("stop", 553, 18, 0.0444), (-1.0, 1.0): ("stop", 865, 17, None),
           (1.0, -1.0): ("crash", 58, "avoid_obstacles")},
    0.033: {(1.1, 1.1): ("stop", 830, 20, 0.0523), (-1.0, 1.0): ("crash", 246, "avoid_obstacles"),
            (1.0, -1.0): ("crash", 86, "avoid_obstacles")},
}


def ending(folder: Path, dt: float, goal: tuple[float, float]) -> tuple:
    sub = load_submission(folder, WEEK7)
    assert sub.ok, sub.errors
    brain = LocalBrain(sub, WEEK7, {"goal": goal})
    sim = Simulator(load_world(WEEK7.world), brain, WEEK7.spec, dt=dt)
    for _ in range(int(round(60.0 / dt))):
        rec = sim.step()
        if rec.collided:
            return ("crash", rec.step, rec.command["state"])
        if rec.command["state"] == "stop":
            x, y, _ = sim.pose
            distance = round(math.hypot(x - goal[0], y - goal[1]), 4)
            return ("stop", rec.step, brain.supervisor.switch_count, distance)
    return ("running after 60 s",)


@pytest.mark.parametrize("dt", sorted(ENDINGS))
def test_solutions_end_every_recorded_goal_as_the_original(dt):
    for goal, expected in ENDINGS[dt].items():
        got = ending(ROOT / "solutions/week7", dt, goal)
        assert got[:3] == expected[:3], (goal, got)
        if len(expected) > 3 and expected[3] is not None:
            assert got[3] == expected[3], (goal, got)


# ../shared/reference/original-simulator.md section 11: the release's week-7 code as shipped (the automaton
# only stops at the goal) in the final world, goal (1.1, 1.1), dt 0.05: true pose, estimate, ticks, wheel
# speeds set, raw IR at some steps, and the crash into the trap's top bar at step 29 (t = 1.45 s).
SECTION_11 = {
    1: ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0, 0), (13.2164, 0.0), (296, 177, 133, 133, 133)),
    2: ((0.010655, 0.001157, 0.216390), (0.012763, 0.0, 0.257183), (2, 0), (9.5137, 3.1416),
        (274, 233, 133, 133, 133)),
    3: ((0.020564, 0.003884, 0.320719), (0.018934, 0.001623, 0.385775), (3, 0), (8.0456, 3.1416),
        (262, 260, 133, 133, 133)),
    5: ((0.037367, 0.011023, 0.483272), (0.036671, 0.008827, 0.514367), (5, 1), (6.5364, 3.1416),
        (241, 302, 133, 133, 133)),
    6: ((0.044225, 0.014868, 0.538854), (0.047783, 0.015106, 0.514367), (6, 2), (6.6447, 0.0),
        (234, 319, 154, 133, 133)),
    10: ((0.065982, 0.032278, 0.742240), (0.068660, 0.029723, 0.771550), (9, 3), (4.7765, 4.4543),
         (205, 391, 249, 154, 133)),
    12: ((0.076910, 0.042553, 0.781108), (0.078341, 0.037999, 0.771550), (10, 4), (4.7818, 4.4490),
         (208, 433, 286, 160, 133)),
}


def test_the_stub_reproduces_the_release_run_of_section_11():
    """The untouched stub is the release's week-7 code: it drives for the goal and hits the trap at 1.45 s."""
    sub = load_submission(ROOT / "assignments/week7", WEEK7)
    assert sub.ok, sub.errors
    brain = LocalBrain(sub, WEEK7, {"goal": (1.1, 1.1)})
    sim = Simulator(load_world(WEEK7.world), brain, WEEK7.spec, dt=0.05)
    for _ in range(60):
        rec = sim.step()
        if rec.step in SECTION_11:
            pose, estimate, ticks, wheels, raw = SECTION_11[rec.step]
            assert [round(c, 6) for c in rec.pose] == list(pose), rec.step
            assert [round(c, 6) for c in rec.command["estimate"]] == list(estimate), rec.step
            assert tuple(rec.ticks) == ticks and tuple(rec.ir_raw) == raw, rec.step
            assert (round(rec.vel_r, 4), round(rec.vel_l, 4)) == wheels, rec.step
        if rec.collided:
            break
    assert (rec.step, round(rec.t, 2)) == (29, 1.45)
    assert [round(c, 4) for c in rec.pose] == [0.1663, 0.1334, 0.7918]
