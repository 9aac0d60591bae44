"""The instructor's hidden week-6 variants are fair: the reference solution passes the grader's own lap
judgement on every one (two laps, no collision, near d_fw, driving along the wall) with the maker's margins
(two laps by 75 s, within 0.03 m of d_fw, never closer than 0.01 m to the wall), and the set covers both
sides."""

from __future__ import annotations

import pytest

from grader.hidden import load_hidden
from instructor_tools.hidden_week6 import reference_run, with_margin


def test_hidden_set_is_present_and_covers_both_sides() -> None:
    data = load_hidden(6)
    assert data is not None and len(data["variants"]) >= 10
    assert {v["direction"] for v in data["variants"]} == {"left", "right"}
    assert len({v["d_fw"] for v in data["variants"]}) >= 2
    assert len({round(v["theta0"], 6) for v in data["variants"]}) >= 6


@pytest.mark.slow
def test_reference_solution_passes_every_hidden_variant() -> None:
    failed = []
    for v in load_hidden(6)["variants"]:
        ok, why, figures = reference_run(v["direction"], v["theta0"], v["d_fw"])
        if not ok or not with_margin(figures, v["d_fw"]):
            failed.append((v, why, figures))
    assert failed == []


def _hidden_points(tmp_path, name: str) -> float:
    import mistakes

    from grader.grading import grade_submission

    folder = mistakes.build("wrong", name, tmp_path, 6)
    result = grade_submission(6, folder, seed=2014, hidden=True, only="week6.laps.hidden")
    (check,) = result["checks"]
    return check["points"] / check["max_points"]


def test_hidden_runs_catch_a_wrong_follow_wall(tmp_path) -> None:
    assert _hidden_points(tmp_path, "week6_pp_sign_flipped") == 0


def test_hidden_runs_use_their_own_d_fw(tmp_path) -> None:
    """The variants set d_fw, so a student's too small d_fw (lost in the visible runs) does not cost them."""
    assert _hidden_points(tmp_path, "week6_d_fw_too_close") == 1


def test_a_week2_mistake_would_sink_the_laps_but_the_runs_use_the_course_parts(tmp_path) -> None:
    """good_week6_week2_ir_divider keeps full marks in test_checks_fail (the lap runs take the course's
    earlier parts, grader.earlier); run on its own code, the same folder crashes into the obstacle."""
    import mistakes

    folder = mistakes.build("wrong", "good_week6_week2_ir_divider", tmp_path, 6)
    ok, why, _ = reference_run("left", 0.0, 0.18, folder)
    assert not ok and "touched an obstacle" in why
