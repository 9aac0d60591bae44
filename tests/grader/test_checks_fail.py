"""The checks can fail: solutions score full marks, stubs score 0, and each wrong version loses exactly the
checks aimed at its mistake while alternative correct versions keep full marks. And the verdicts stay: every
kept version and stub, hidden checks included, grades exactly as tests/data/verdicts/seed2014.json says
(status and points of every check, seed 2014), the snapshot made before issue 24's speed work; a change of
checks that changes a verdict says why and rewrites it (`python tests/grader/verdict_matrix.py --kernel
Haswell --snapshot`)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from mistakes import DATA, read_mistake
from verdict_matrix import SNAPSHOT
from wrong_submissions import ROOT, build, week_of

from grader.grading import grade_submission
from simiam.course.weeks import all_weeks, week_numbers

# What each kept wrong version must lose is said in its own `# aims:` line (with why, where it also loses a
# scenario check): one place, read by this test and by `grade selfcheck` alike.
EXPECTED_FAILURES = {p.stem: set(read_mistake(p).aims or ())
                     for p in sorted((DATA / "wrong").glob("*.patch"))}


VERDICTS = json.loads(SNAPSHOT.read_text())["verdicts"]


def _failed(result: dict) -> set[str]:
    return {c["id"] for c in result["checks"] if c["status"] != "passed" and c["visibility"] != "hidden"}


def _verdicts(result: dict) -> dict[str, list]:
    """{check id: [status, points]}, as the snapshot holds them."""
    return {c["id"]: [c["status"], round(c["points"], 9)] for c in result["checks"]}


# what the message of a lost check must say (the right reason, in words a student can act on)
MESSAGES = {
    "week3_integral_dt_again": {"week3.pid.integral": "Ki * (E_k + e_k * dt)"},
    "week3_derivative_from_sum": {"week3.pid.derivative": "Kd * (e_k - e_k_1) / dt"},
    "week3_gains_in_execute": {"week3.pid.memory": "execute overwrote Kp/Ki/Kd"},
    "week3_single_wrap": {"week3.go_to_goal.error_wrap": "wrapped into [-pi, pi]"},
    "week3_theta_g_from_origin": {"week3.go_to_goal.theta_g": "from the robot's position"},
    "week3_theta_g_atan2_swapped": {"week3.go_to_goal.theta_g": "3.1416 rad off, expected 2.3562"},
    "week2_ir_no_divider": {"week2.ir.table": "wildly off (-8.886e+13 m)",
                            "week2.ir.simulator": "wildly off (-8.886e+13 m)"},
    "week2_half_turn": {"week2.go_to_angle.reaches_theta_d": "ended 0.032 rad away"},
    "week2_ir_degree7_rounded": {"week2.ir.table": "so your volts are right"},
    "week2_ir_wrong_divider": {"week2.ir.table": "divide by 500 to get volts"},
    "week2_uni_to_diff_over_3R": {"week2.uni_to_diff.round_trip": "v and w both came out 0.6667 times"},
    "week2_uni_to_diff_times_R": {"week2.uni_to_diff.round_trip": "v and w both came out 0.0011 times"},
    "week2_full_L": {"week2.uni_to_diff.round_trip": "w came out 2 times the asked: check L/2 vs L"},
    "week2_swapped_wheels": {"week2.uni_to_diff.round_trip": "v is right and w reversed: check which wheel"},
    "week2_spin_unequal": {"week2.uni_to_diff.spin": "opposite but not equal (one 0.5 times"},
    "week4_theta_ao_swapped": {"week4.avoid.heading": "atan2(u_ao[1], u_ao[0])"},
    "week4_ao_error_not_wrapped": {"week4.avoid.heading": "wrapped into [-pi, pi]"},
    "week4_gains_from_readings": {"week4.avoid.symmetric_gains": "sensor_gains must be fixed numbers"},
    "week4_stops_near_walls": {"week4.avoid.week4_world": "drove only 0.00 m"},
    "week5_blend_only_goal": {"week5.blend.between": "it leaves out u_ao",
                              "week5.switching.reach_goal": "(-1, 1) came within 3.0 mm of an obstacle"},
    "week5_blend_subtracts_u_ao": {"week5.blend.between": "it subtracts u_ao",
                                   "week5.switching.reach_goal": "so the blend steered it there"},
    "week5_blend_jumps": {"week5.blend.continuous": "changing only the length of u_ao"},
    "week5_switching_unsafe_last": {"week5.switching.states": "expected 'avoid_obstacles'",
                                    "week5.switching.reach_goal": "events called for avoid_obstacles"},
    "week5_switching_chatters": {"week5.switching.switch_rate": "chatters between controllers"},
    "week5_switching_independent_ifs": {"week5.switching.states": "switched 2 times in that one step"},
    "week5_switching_chatters_unreported": {"week5.switching.switch_rate": "27.5 switches per second"},
    "week6_d_fw_too_close": {"week6.laps.left": "your d_fw = 0.1 m: touched an obstacle at t = 2.75 s"},
    "week6_u_fw_no_tangent": {"week6.laps.left": "it turned on average 2.87 rad/s once it found the wall"},
    "week6_direction_misspelt": {"week6.supervisor.settings": "your fw_direction was 'rigth'"},
    "week6_ties_prefer_last": {"week6.follow_wall.sensors": "order): you left out sensor 4, which"},
    "week6_pp_sign_flipped": {"week6.follow_wall.distance": "zero at d_fw"},
    "week6_perpendicular_reversed": {"week6.follow_wall.perpendicular": "pointing away from the wall"},
    "week6_pp_unit_vector": {"week6.follow_wall.distance": "expected u_fw_p - d_fw * u_fw_p / |u_fw_p|"},
    "week7_sigma_cramer_sign": {"week7.sliding.sigma": "sigma_2 has the wrong sign"},
    "week7_sigma_transposed": {"week7.sliding.sigma": "as the ROWS; solve"},
    "week7_progress_strict": {"week7.progress.made": "a step with no encoder tick"},
    "week7_progress_point_never_set": {"week7.navigate.release_goal": "calls self.set_progress_point() when"},
    "week7_stub_thresholds": {"week7.navigate.release_goal": "tune d_at_obs and d_unsafe"},
}

# what it must NOT say: a hint pointing at a part the numbers show is right (issue 31)
NOT_SAID = {
    "week2_ir_degree7_rounded": {"week2.ir.table": "divide by 500"},
    "week2_uni_to_diff_over_3R": {"week2.uni_to_diff.round_trip": "L/2 vs L"},
    "week2_uni_to_diff_times_R": {"week2.uni_to_diff.round_trip": "L/2 vs L"},
    "week2_spin_unequal": {"week2.uni_to_diff.spin": "needs opposite, non-zero"},
    "week2_full_L": {"week2.uni_to_diff.round_trip": "which wheel is which"},
}


@pytest.mark.parametrize("name", sorted(EXPECTED_FAILURES))
def test_wrong_version_loses_exactly_its_checks(name: str, tmp_path: Path) -> None:
    result = grade_submission(week_of(name), build(name, tmp_path), seed=2014, hidden=True)
    assert result["status"] == "graded"
    assert _verdicts(result) == VERDICTS[name]
    assert _failed(result) == EXPECTED_FAILURES[name]
    visible = [c for c in result["checks"] if c["visibility"] != "hidden"]
    lost = {c["id"] for c in visible if c["points"] < c["max_points"]}
    assert lost == EXPECTED_FAILURES[name]
    checks = {c["id"]: c for c in result["checks"]}
    for check_id, words in MESSAGES.get(name, {}).items():
        assert words in checks[check_id]["message"], checks[check_id]["message"]
    for check_id, words in NOT_SAID.get(name, {}).items():
        assert words not in checks[check_id]["message"], checks[check_id]["message"]
    for c in visible:  # the hidden checks' words are tested with the hidden sets (test_hidden_*)
        if c["status"] == "passed":
            continue
        assert c["status"] == "failed", c  # never an error: a wrong answer is a failure with a reason
        # numbers students paste back into Python use an ASCII minus; no absurd percentages
        figures = c["message"].replace("more than 1000 %", "")  # what 'wildly off' says instead
        assert "\u2212" not in c["message"] and not re.search(r"\d{4,}(\.\d+)? ?%", figures)
        if c["kind"] == "scenario":
            assert "Hint:" in c["message"], c["message"]


@pytest.mark.parametrize("week", week_numbers())
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_solutions_score_full_marks_with_hidden_checks(week: int, seed: int) -> None:
    result = grade_submission(week, ROOT / "solutions" / f"week{week}", seed=seed, hidden=True)
    assert result["status"] == "graded"
    failures = [c["message"] for c in result["checks"] if c["status"] != "passed"]
    assert result["score"] == result["max_score"], failures


@pytest.mark.parametrize("week", [w.number for w in all_weeks() if w.blocks])
def test_untouched_stubs_score_zero(week: int) -> None:
    result = grade_submission(week, ROOT / "assignments" / f"week{week}", seed=2014, hidden=True)
    assert result["status"] == "graded"
    assert _verdicts(result) == VERDICTS[f"assignments/week{week}"]
    assert result["score"] == 0
    assert all(c["status"] != "passed" for c in result["checks"])


def test_week1_stub_runs_and_stays_still() -> None:
    result = grade_submission(1, ROOT / "assignments" / "week1", seed=2014)
    assert result["score"] == result["max_score"] == 2.0
