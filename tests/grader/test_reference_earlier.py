"""Week 7's navigation runs the course's versions of the earlier weeks' parts (grader.earlier, as weeks 5
and 6 do), so a week-2 mistake carried into week 7 costs nothing there. Where the course's versions are not
at hand (a student's own installation) the runs use the student's own code and the message says so: then the
same mistake loses the navigation."""

from __future__ import annotations

from pathlib import Path

import mistakes
import pytest

from grader.earlier import OWN_CODE_NOTE
from grader.grading import grade_submission


@pytest.fixture(scope="module")
def odometry_wrong(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return mistakes.build("submissions", "week7_week2_odometry_doubled", tmp_path_factory.mktemp("w7"), 7)


def _lost(result: dict) -> set[str]:
    return {c["id"] for c in result["checks"] if c["status"] != "passed"}


def test_an_earlier_weeks_mistake_costs_nothing_in_week_7(odometry_wrong: Path) -> None:
    result = grade_submission(7, odometry_wrong, seed=2014)
    assert result["status"] == "graded" and _lost(result) == set()


def test_without_the_course_versions_the_same_mistake_loses_the_navigation(
        odometry_wrong: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("grader.earlier.reference_folder", lambda *args, **kwargs: None)
    result = grade_submission(7, odometry_wrong, seed=2014)
    assert "week7.navigate.release_goal" in _lost(result)
    navigation = next(c for c in result["checks"] if c["id"] == "week7.navigate.release_goal")
    assert OWN_CODE_NOTE in navigation["message"]
