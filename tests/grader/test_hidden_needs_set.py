"""`grade --hidden` without the hidden set (a student's wheel): it says the hidden checks need the course
checkout and run at official grading, instead of showing each one as an ERROR row."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from grader.cli import main
from grader.hidden import WEEKS_WITH_DATA, missing_hidden_set

ROOT = Path(__file__).resolve().parents[2]


def test_the_weeks_with_a_hidden_set_are_the_ones_whose_checks_read_it() -> None:
    held = {int(m.group(1)) for p in (ROOT / "instructor_tools" / "hidden").glob("week*.json")
            if (m := re.fullmatch(r"week(\d)\.json", p.name))}
    # a check reads it through grader.practice.variants_to_run (the practice set with --practice)
    readers = {w for w in range(1, 8)
               if re.search(r"load_hidden\(|variants_to_run\(ctx, ",
                            (ROOT / "grader" / "checks" / f"week{w}.py").read_text(encoding="utf-8"))}
    assert held == readers == set(WEEKS_WITH_DATA)


def test_hidden_without_the_set_is_refused_in_words(tmp_path: Path, monkeypatch, capsys) -> None:
    monkeypatch.setenv("SIMIAM_HIDDEN", str(tmp_path / "no-hidden-set"))  # as in a student's wheel
    code = main(["week5", str(ROOT / "assignments" / "week5"), "--hidden", "--out", str(tmp_path / "out")])
    said = capsys.readouterr()
    assert code == 2 and not (tmp_path / "out").exists()
    assert "--hidden runs the hidden checks of week 5" in said.err
    assert "course checkout" in said.err and "official grading" in said.err
    assert "ERROR" not in said.out + said.err and "hidden set is not here" not in said.out
    missing_hidden_set([1, 2, 3])  # their hidden checks draw from the seed alone: nothing is missing
    with pytest.raises(ValueError, match="week 4, week 7"):
        missing_hidden_set([4, 7])
