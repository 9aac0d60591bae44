"""The late policy's numbers, exactly: intervals rounded up, the cap, Canvas's floor, the grace period,
hours, extensions; and the policy options read strictly (a deadline without a time zone is refused)."""

from __future__ import annotations

import importlib.util
from datetime import datetime, timedelta, timezone
from pathlib import Path

import pytest

from grader.batch.identity import Identity
from grader.batch.intake import IntakeError, IntakeOptions
from grader.batch.late import (
    LatePolicy,
    PolicyError,
    late_record,
    parse_duration,
    parse_extension,
    parse_penalty,
)
from grader.batch.late_apply import settle_late, with_late_section

DUE = datetime(2026, 3, 1, 23, 59, tzinfo=timezone(timedelta(hours=-5)))
H, D = 3600, 86400


def _wrong() -> object:
    path = Path(__file__).parents[1] / "data" / "batch" / "wrong_intake.py"
    spec = importlib.util.spec_from_file_location("wrong_intake", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def percent(seconds: float, rate: float, interval_s: int, cap: float | None, grace_s: int) -> float:
    """The penalty percent late_record charges a 10/10 submission ``seconds`` after the deadline."""
    policy = LatePolicy(DUE, rate, interval_s, cap_percent=cap, grace_s=grace_s)
    when = (DUE + timedelta(seconds=seconds)).isoformat()
    return late_record(policy, when, None, 10.0, 10.0)["penalty_percent"]


# (seconds late, rate %, interval, cap %, grace s) -> penalty %
CASES = [
    ((26 * H, 10.0, D, None, 0), 20.0),  # 26 h late: two days, rounded up
    ((24 * H, 10.0, D, None, 0), 10.0),  # exactly a day: one
    ((1, 10.0, D, None, 0), 10.0),  # one second: a whole day
    ((10 * D, 10.0, D, 50.0, 0), 50.0),  # capped
    ((61 * 60, 2.0, H, None, 0), 4.0),  # 61 minutes at 2 %/hour: two hours
    ((14 * 60, 10.0, D, None, 15 * 60), 0.0),  # within 15 minutes' grace
    ((24 * H + 10 * 60, 10.0, D, None, 15 * 60), 20.0),  # past grace: charged from the deadline
    ((-60, 10.0, D, None, 0), 0.0),
]  # early


@pytest.mark.parametrize(("args", "expected"), CASES)
def test_penalty_percent(args: tuple, expected: float) -> None:
    assert percent(*args) == expected, f"{args}: {percent(*args)} != {expected}"


def test_each_wrong_penalty_rule_is_caught() -> None:
    wrong = _wrong()
    for name in (
        "penalty_percent_floor",
        "penalty_percent_no_cap",
        "penalty_percent_grace_shifts",
        "penalty_percent_no_grace",
    ):
        rule = getattr(wrong, name)
        caught = [args for args, expected in CASES if rule(*args) != expected]
        assert caught, f"{name} passes every case of CASES: the table cannot tell it from the right rule"


def test_record_points_floor_and_extension() -> None:
    # Canvas's own example (lms-formats.md section 7): 10 points, 10 %/day, 26 h late, raw 6, floor 50 %:
    # min(20, 6/10 - 50 = 10) % = 1 point, so 5.
    policy = LatePolicy(DUE, 10.0, D, floor_percent=50.0)
    record = late_record(policy, (DUE + timedelta(hours=26)).isoformat(), None, 6.0, 10.0)
    assert (record["penalty_percent"], record["penalty_points"], record["score_before"]) == (10.0, 1.0, 6.0)
    assert record["seconds_late"] == 26 * H and record["note"] == "2 days late"
    # the penalty never takes the score below zero
    harsh = late_record(LatePolicy(DUE, 100.0, D), (DUE + timedelta(days=3)).isoformat(), None, 2.0, 10.0)
    assert harsh["penalty_points"] == 2.0
    # an extension replaces the deadline: two days more, submitted 26 h late, is on time
    until = parse_extension("2d", DUE, None)
    assert until == DUE + timedelta(days=2)
    on_time = late_record(LatePolicy(DUE, 10.0, D), (DUE + timedelta(hours=26)).isoformat(), until, 6.0, 10.0)
    assert (on_time["penalty_points"], on_time["extension_until"], on_time["note"]) == (
        0.0,
        until.isoformat(),
        "on time (extension)",
    )
    assert parse_extension("3", DUE, None) == DUE + timedelta(days=3)
    assert parse_extension("2026-03-04T12:00:00+00:00", DUE, None) == datetime(
        2026, 3, 4, 12, tzinfo=timezone.utc
    )
    # no submission time: never charged, the note says why
    unknown = late_record(LatePolicy(DUE, 10.0, D), "", None, 6.0, 10.0, late_flag=True, platform="canvas")
    assert (
        unknown["penalty_points"] == 0.0
        and unknown["note"] == "marked late by Canvas, no submission time: give --times"
    )


def test_policy_options_are_read_strictly() -> None:
    assert parse_penalty("10%/day") == (10.0, D) and parse_penalty("2.5% / hour") == (2.5, H)
    assert parse_duration("15m") == 900 and parse_duration("1h30m") == 5400 and parse_duration("90") == 5400
    for bad in ("10/week", "ten%/day", "-5%/day", "150%/day"):
        with pytest.raises(PolicyError):
            parse_penalty(bad)
    with pytest.raises(IntakeError, match="no time zone"):
        IntakeOptions(deadline="2026-03-01T23:59").policy()
    assert IntakeOptions(deadline="2026-03-01T23:59", timezone="America/New_York").policy().deadline == DUE
    with pytest.raises(IntakeError, match="need --deadline"):
        IntakeOptions(late_penalty="10%/day").policy()
    with pytest.raises(IntakeError, match="not a time zone"):
        IntakeOptions(deadline="2026-03-01T23:59", timezone="Mars/Olympus").policy()


def test_a_changed_policy_is_reapplied_to_the_stored_result() -> None:
    identity = Identity(id="7", submitted_at=(DUE + timedelta(hours=30)).isoformat())
    result = {"status": "graded", "score": 8.0, "max_score": 10.0}
    assert settle_late(result, identity, LatePolicy(DUE, 10.0, D), None) is True
    assert (result["score"], result["late"]["score_before"]) == (6.0, 8.0)
    assert settle_late(result, identity, LatePolicy(DUE, 10.0, D), None) is False  # the same: unchanged
    assert settle_late(result, identity, LatePolicy(DUE, 5.0, D), None) is True
    assert result["score"] == 7.0
    assert (
        settle_late(result, identity, None, None) is True and result["score"] == 8.0 and "late" not in result
    )
    forged = {"status": "graded", "score": 8.0, "max_score": 10.0, "late": {"score_before": 1e9}}
    assert settle_late(forged, identity, LatePolicy(DUE, 5.0, D), None) is None  # graded again instead


def test_the_page_section_is_replaced_only_where_the_grader_put_it() -> None:
    late = {
        "seconds_late": 30 * H,
        "penalty_points": 2.0,
        "penalty_percent": 20.0,
        "score_before": 8.0,
        "deadline": DUE.isoformat(),
        "submitted_at": "x",
        "extension_until": None,
        "note": "2 days late",
    }
    student_text = "&lt;!-- simiam:late --&gt; and <!-- simiam:late -->printed<!-- /simiam:late -->"
    page = f"<html><body class=r><p>{student_text}</p></body></html>"
    once = with_late_section(page, late)
    assert once.count("Late penalty: 2 points") == 1 and student_text in once
    twice = with_late_section(once, {**late, "penalty_points": 1.0, "penalty_percent": 10.0})
    assert (
        "Late penalty: 1 point (" in twice and "Late penalty: 2 points" not in twice and student_text in twice
    )
    assert with_late_section(twice, None) == page
