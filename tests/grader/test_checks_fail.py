"""The checks can fail: solutions score full marks, stubs score 0, and each wrong version loses exactly the
checks aimed at its mistake while alternative correct versions keep full marks."""

from __future__ import annotations

from pathlib import Path

import pytest
from wrong_submissions import ROOT, build, week_of

from grader.grading import grade_submission

# visible checks each wrong version must fail (and no others)
EXPECTED_FAILURES = {
    "week2_swapped_wheels": {"week2.uni_to_diff.round_trip", "week2.go_to_angle.reaches_theta_d"},
    "week2_full_L": {"week2.uni_to_diff.round_trip"},
    "week2_odometry_half_L": {"week2.odometry.heading", "week2.odometry.course_test",
                              "week2.go_to_angle.reaches_theta_d"},
    "week2_odometry_sin_cos": {"week2.odometry.direction", "week2.odometry.course_test"},
    "week2_ir_wrong_divider": {"week2.ir.table", "week2.ir.simulator"},
    "week3_no_wrap": {"week3.go_to_goal.error_wrap"},
    "week3_integral_no_dt": {"week3.pid.integral"},
    "week3_derivative_flipped": {"week3.pid.derivative"},
    "week3_state_not_kept": {"week3.pid.memory"},
    # the course's overshoot takes |r - y| at the extreme sample, so a slow approach counts too
    "week3_weak_gains": {"week3.pid.settle_time", "week3.pid.overshoot"},
    "week3_ensure_w_clamps": {"week3.ensure_w.keeps_w", "week3.ensure_w.gives_up_v"},
    "week4_transposed_rotation": {"week4.transform.matrix", "week4.avoid.week4_world"},
    "week4_no_robot_translation": {"week4.sensor_geometry.world_frame"},
    "week4_asymmetric_gains": {"week4.avoid.symmetric_gains"},
    "good_week2_numpy": set(),
    "good_week2_midpoint": set(),
    "good_week2_interp": set(),
    "good_week3_other_gains": set(),
}


def _failed(result: dict) -> set[str]:
    return {c["id"] for c in result["checks"] if c["status"] != "passed"}


@pytest.mark.parametrize("name", sorted(EXPECTED_FAILURES))
def test_wrong_version_loses_exactly_its_checks(name: str, tmp_path: Path) -> None:
    result = grade_submission(week_of(name), build(name, tmp_path), seed=2014)
    assert result["status"] == "graded"
    assert _failed(result) == EXPECTED_FAILURES[name]
    lost = {c["id"] for c in result["checks"] if c["points"] < c["max_points"]}
    assert lost == EXPECTED_FAILURES[name]


@pytest.mark.parametrize("week", [1, 2, 3, 4])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_solutions_score_full_marks_with_hidden_checks(week: int, seed: int) -> None:
    result = grade_submission(week, ROOT / "solutions" / f"week{week}", seed=seed, hidden=True)
    assert result["status"] == "graded"
    failures = [c["message"] for c in result["checks"] if c["status"] != "passed"]
    assert result["score"] == result["max_score"], failures


@pytest.mark.parametrize("week", [2, 3, 4])
def test_untouched_stubs_score_zero(week: int) -> None:
    result = grade_submission(week, ROOT / "assignments" / f"week{week}", seed=2014, hidden=True)
    assert result["status"] == "graded"
    assert result["score"] == 0
    assert all(c["status"] != "passed" for c in result["checks"])


def test_week1_stub_runs_and_stays_still() -> None:
    result = grade_submission(1, ROOT / "assignments" / "week1", seed=2014)
    assert result["score"] == result["max_score"] == 2.0
