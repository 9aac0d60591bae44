"""Week 7 grades its own blocks: earlier weeks' blocks run as the course ships them (Week.reference_earlier),
so a week-2 mistake carried into week 7 costs nothing there, and the feedback says which block was
replaced. Without the replacement the same submission loses the navigation."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import mistakes
import pytest

from grader.grading import grade_submission
from simiam.course.weeks import get_week


@pytest.fixture(scope="module")
def odometry_wrong(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return mistakes.build("submissions", "week7_week2_odometry_doubled", tmp_path_factory.mktemp("w7"), 7)


def _lost(result: dict) -> set[str]:
    return {c["id"] for c in result["checks"] if c["status"] != "passed"}


def test_an_earlier_weeks_mistake_costs_nothing_in_week_7_and_is_named(odometry_wrong: Path) -> None:
    result = grade_submission(7, odometry_wrong, seed=2014)
    assert result["status"] == "graded" and _lost(result) == set()
    assert any("qb_supervisor.py: QBSupervisor.update_odometry (week 2) ran as the course ships it" in n
               for n in result["notices"]), result["notices"]


def test_without_the_course_versions_the_same_mistake_loses_the_navigation(
        odometry_wrong: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    own = dataclasses.replace(get_week(7), reference_earlier=False)
    monkeypatch.setattr("grader.grading.get_week", lambda week: own)
    result = grade_submission(7, odometry_wrong, seed=2014)
    assert "week7.navigate.release_goal" in _lost(result)
    assert not any("ran as the course ships it" in n for n in result["notices"])
