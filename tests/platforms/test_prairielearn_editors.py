"""The PrairieLearn question of every week opens an editor for exactly the files holding a block new that
week, found here from the handout itself (the files whose blocks are this week's placeholders), not from
the week's declaration the package reads: the two must agree. A week with nothing to write (week 1) opens
none, and its empty submission grades the handout."""

from __future__ import annotations

from pathlib import Path

import pytest
from mistakes import ROOT

from grader.platforms.handout import handout_files
from grader.platforms.official import SubmissionRefused, grade_upload, read_secret, write_secret
from grader.platforms.prairielearn import editor_files
from simiam.course.blocks import find_blocks
from simiam.course.weeks import placeholder_for, week_numbers


def _with_new_blocks(week: int, files: dict[str, str]) -> list[str]:
    new = set()
    for name, text in files.items():
        for block in find_blocks(text, name) if name.endswith(".py") else []:
            spec = (placeholder_for(name, block.scope, block.occurrence, week)
                    or placeholder_for(name, block.scope, block.occurrence))
            if spec is not None and spec.week == week:
                new.add(name)
    return sorted(new)


@pytest.mark.parametrize("week", list(week_numbers()))
def test_editors_are_the_files_with_this_weeks_blocks(week: int, tmp_path: Path):
    files = handout_files(week, ROOT)
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    editors = editor_files(week, tmp_path)
    assert editors == _with_new_blocks(week, files)
    if week == 3:   # the case issue 23 saw: no editor for week 2's differential_drive.py nor quickbot.py
        assert editors == ["go_to_goal.py", "qb_supervisor.py"]


@pytest.fixture
def official_env(monkeypatch):
    """grade_upload points $SIMIAM_HIDDEN and $SIMIAM_HANDOUT at the bundle's folders: undone after."""
    monkeypatch.setenv("SIMIAM_HIDDEN", "")
    monkeypatch.setenv("SIMIAM_HANDOUT", "")


def _handout(week: int, folder: Path) -> Path:
    folder.mkdir()
    for name, text in handout_files(week, ROOT).items():
        (folder / name).write_text(text)
    return folder


@pytest.mark.sandbox
def test_a_week_with_nothing_to_write_grades_the_handout_when_nothing_is_submitted(tmp_path, official_env):
    # week 1's question opens no editor, so PrairieLearn submits no file: the handout is what is graded
    assert editor_files(1, _handout(1, tmp_path / "starter")) == []
    (tmp_path / "student").mkdir()
    secret = read_secret(write_secret(tmp_path / "secret", 1, 2014, None))
    result = grade_upload(tmp_path / "student", secret, fill_from=tmp_path / "starter",
                          note_filled=False)
    assert result["status"] == "graded" and result["score"] == result["max_score"] > 0
    assert not [n for n in result.get("notices", []) if "missing from your submission" in n]


@pytest.mark.sandbox
def test_an_empty_upload_in_a_week_with_code_to_write_is_still_refused(tmp_path, official_env):
    _handout(3, tmp_path / "starter")
    (tmp_path / "student").mkdir()
    secret = read_secret(write_secret(tmp_path / "secret", 3, 2014, None))
    with pytest.raises(SubmissionRefused, match="none of the week-3 files"):
        grade_upload(tmp_path / "student", secret, fill_from=tmp_path / "starter", note_filled=False)
