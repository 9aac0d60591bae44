"""The PrairieLearn question of every week opens an editor for exactly the files holding a block new that
week, found here from the handout itself (the files whose blocks are this week's placeholders), not from
the week's declaration the package reads: the two must agree."""

from __future__ import annotations

from pathlib import Path

import pytest
from mistakes import ROOT

from grader.platforms.handout import handout_files
from grader.platforms.prairielearn import editor_files
from simiam.course.blocks import find_blocks
from simiam.course.placeholders import placeholder_for
from simiam.course.weeks import week_numbers


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
