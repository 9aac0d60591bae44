"""`grade handout weekN`: the week's files (generated from solutions/, earlier blocks filled) and README, as
a folder and a zip; nothing of later weeks and no solution code of the week's own blocks."""

from __future__ import annotations

import zipfile
from pathlib import Path

import pytest
from mistakes import ROOT

from grader.cli import main
from grader.platforms import handout
from grader.platforms.handout import HandoutLeak, handout_files, leaks
from simiam.course.stubs import generate
from simiam.course.weeks import week_numbers


@pytest.mark.parametrize("week", week_numbers())
def test_the_handout_is_the_weeks_stubs_and_readme_as_folder_and_zip(tmp_path: Path, week: int):
    assert main(["handout", f"week{week}", "--out", str(tmp_path), "--course", str(ROOT)]) == 0
    folder = tmp_path / f"week{week}"
    stubs = {k.rsplit("/", 1)[1]: v for k, v in generate(ROOT / "solutions").files.items()
             if k.startswith(f"assignments/week{week}/")}
    expected = {**stubs, "README.md": (ROOT / "assignments" / f"week{week}" / "README.md").read_text()}
    practice = ROOT / "grader" / "practice" / f"week{week}.json"  # grade weekN --practice's variants
    if week >= 3:
        expected[handout.PRACTICE_FILE] = practice.read_text()
    assert {p.name: p.read_text() for p in folder.iterdir()} == expected
    with zipfile.ZipFile(tmp_path / f"week{week}.zip") as archive:
        assert {n: archive.read(n).decode() for n in archive.namelist()} == \
            {f"week{week}/{n}": t for n, t in expected.items()}
    solution = ROOT / "solutions" / f"week{week}"
    assert {p.name for p in folder.glob("*.py")} == {p.name for p in solution.glob("*.py")}
    assert leaks(week, expected, ROOT) == []
    assert not [n for n in expected if "hidden" in n]  # the instructor's hidden set never ships


def test_week3_has_no_week4_file_and_no_week3_answer(tmp_path: Path):
    files = handout_files(3, ROOT)
    assert "avoid_obstacles.py" not in files
    assert "theta_g = math.atan2(u_y, u_x)" not in files["go_to_goal.py"]
    assert "theta_g = math.atan2(u_y, u_x)" in handout_files(4, ROOT)["go_to_goal.py"]   # filled a week later


@pytest.mark.parametrize("leak", ["solution_file", "later_file", "readme_mentions_later", "later_block"])
def test_a_leak_is_found_and_nothing_is_written(tmp_path: Path, monkeypatch, leak: str):
    files = handout_files(3, ROOT)
    if leak == "solution_file":
        files["go_to_goal.py"] = (ROOT / "solutions" / "week3" / "go_to_goal.py").read_text()
    elif leak == "later_file":
        files["avoid_obstacles.py"] = (ROOT / "assignments" / "week4" / "avoid_obstacles.py").read_text()
    elif leak == "readme_mentions_later":
        files["README.md"] += "\nNext week you write avoid_obstacles.py.\n"
    else:
        files["go_to_goal.py"] += "\n\ndef later():\n    # START CODE BLOCK\n    pass\n    # END CODE BLOCK\n"
    assert leaks(3, files, ROOT)
    monkeypatch.setattr(handout, "handout_files", lambda week, course: files)
    with pytest.raises(HandoutLeak):
        handout.build_handout(3, tmp_path / "out", ROOT)
    assert not (tmp_path / "out").exists()
    assert main(["handout", "week3", "--out", str(tmp_path / "out"), "--course", str(ROOT)]) == 2


def test_an_existing_handout_folder_is_not_overwritten(tmp_path: Path, capsys):
    (tmp_path / "week2").mkdir()
    (tmp_path / "week2" / "mine.py").write_text("keep me\n")
    assert main(["handout", "week2", "--out", str(tmp_path), "--course", str(ROOT)]) == 2
    assert "already exists" in capsys.readouterr().err
    assert (tmp_path / "week2" / "mine.py").read_text() == "keep me\n"


def test_without_a_course_checkout_the_command_says_where_it_looked(tmp_path: Path, capsys):
    assert main(["handout", "week2", "--out", str(tmp_path / "o"), "--course", str(tmp_path)]) == 2
    assert "no course checkout" in capsys.readouterr().err
