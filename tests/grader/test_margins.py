"""Margins (grader.margins) say honestly how far each judged figure is from its limit: the run nearest the
limit is the one kept, a missing figure fails, a collision is 'touching', and a check's margins agree with
its verdict (a passed check has every figure on the passing side, a failed one at least one past it)."""

from __future__ import annotations

import pytest
from wrong_submissions import ROOT, build

from grader.grading import grade_submission
from grader.margins import CLEARANCE, Limit, Margins, passes, words

TURNING = Limit("turning rate", "rad/s", 1.2, above=False)


def test_the_run_nearest_the_limit_is_kept_and_a_missing_figure_is_the_worst() -> None:
    margins = Margins()
    margins.add(CLEARANCE, 0.03, "a")
    margins.add(CLEARANCE, 0.01, "b")
    margins.add(CLEARANCE, 0.02, "c")
    margins.add(TURNING, 0.5, "a")
    margins.add(TURNING, None, "b")
    margins.add(TURNING, 2.0, "c")
    clearance, turning = margins.to_json()
    assert (clearance["run"], clearance["value"], clearance["margin"]) == ("b", 0.01, 0.01)
    assert (turning["run"], turning["value"], turning["margin"]) == ("b", None, None)
    assert passes(clearance) and not passes(turning)


@pytest.mark.parametrize(("limit", "value", "passed", "said"), [
    (CLEARANCE, 0.0236, True, "clearance 0.0236 m (limit > 0 m): 0.0236 m to spare [run]"),
    (CLEARANCE, 0.0, False, "clearance 0 m (limit > 0 m): touching: a collision [run]"),
    (Limit("clearance", "m", 0.007, above=True), 0.003, False,
     "clearance 0.003 m (limit >= 0.007 m): 0.004 m past it [run]"),
    (Limit("laps", "", 2, above=True), 2, True, "laps 2 (limit >= 2): 0 to spare [run]"),
    (TURNING, 2.87, False, "turning rate 2.87 rad/s (limit <= 1.2 rad/s): 1.67 rad/s past it [run]"),
    (Limit("arrival time", "s", 60.0, above=False), None, False,
     "arrival time none (limit <= 60 s): the run ended without it [run]"),
])
def test_each_side_of_a_limit_in_words(limit: Limit, value, passed: bool, said: str) -> None:
    entry = limit.entry(value, "run")
    assert passes(entry) is passed
    assert words(entry) == said


def _agree(result: dict) -> list[str]:
    """What contradicts: a passed scenario check with a figure past its limit, or a failed one (its runs
    not broken) whose figures all pass."""
    wrong = []
    for c in result["checks"]:
        entries = c["details"].get("margins") if c["kind"] == "scenario" else None
        if not entries:
            continue
        ok = [passes(e) for e in entries]
        if c["status"] == "passed" and not all(ok):
            wrong.append(f"{c['id']} passed with {[words(e) for e in entries if not passes(e)]}")
        if c["status"] == "failed" and all(ok):
            wrong.append(f"{c['id']} failed ({c['message'][:100]}) with every figure to spare")
    return wrong


@pytest.mark.parametrize("name", ["week5_blend_only_goal", "week6_u_fw_no_tangent", "week7_no_unsafe"])
def test_margins_agree_with_the_verdicts_of_wrong_versions_and_the_solution(name: str, tmp_path) -> None:
    wrong = build(name, tmp_path)
    week = int(name[4])
    for folder in (wrong, ROOT / "solutions" / f"week{week}"):
        result = grade_submission(week, folder, seed=2014)
        assert any(c["details"].get("margins") for c in result["checks"])
        assert _agree(result) == []


def test_a_margin_that_contradicts_its_verdict_is_caught() -> None:
    """The agreement test can fail: a passed check holding a figure past its limit."""
    entry = TURNING.entry(2.87, "run")
    result = {"checks": [{"id": "x", "kind": "scenario", "status": "passed", "message": "",
                          "details": {"margins": [entry]}}]}
    assert _agree(result) == ["x passed with ['turning rate 2.87 rad/s (limit <= 1.2 rad/s): 1.67 rad/s past "
                              "it [run]']"]


def test_overshoot_is_shown_as_the_percentage_students_read() -> None:
    """`grade selfcheck` printed "overshoot 32.12 (limit <= 0.1)" where every message says percent (issue
    31); the stored figures stay fractions, and a result read back from JSON reads the same."""
    import json

    from grader.checks.week3 import OVERSHOOT
    from grader.margins import words

    entry = json.loads(json.dumps(OVERSHOOT.entry(0.3212, "goal (0, -1)")))
    assert entry["value"] == 0.3212 and entry["limit"] == 0.1
    said = words(entry)
    assert said == "overshoot 32.12 % (limit <= 10 %): 22.1 % past it [goal (0, -1)]", said
    assert "0.1)" not in said
    assert words(OVERSHOOT.entry(0.0171, "")) == "overshoot 1.71 % (limit <= 10 %): 8.29 % to spare"
