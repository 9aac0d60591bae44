"""One default-folder rule for `grade`, `simiam run` and `simiam migrate` (issue 11): the current folder if
it is named weekN, else ./weekN, else ./assignments/weekN, else a clear message (exit 2)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from grader.cli import main as grade_main
from simiam.cli import main as simiam_main
from simiam.course import folders
from simiam.course.folders import WeekFolderNotFound, default_week_folder, week_folder

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("layout, expected", [
    ("week3", "week3"),                         # inside the week folder
    ("course/week3", "course/week3"),           # the week folder is below the current one
    ("assignments/week3", "assignments/week3"),  # the course checkout
])
def test_the_rule_finds_the_week_folder(tmp_path: Path, monkeypatch, layout: str, expected: str) -> None:
    (tmp_path / layout).mkdir(parents=True)
    cwd = tmp_path / layout if layout == "week3" else tmp_path / layout.split("/")[0]
    if layout == "assignments/week3":
        cwd = tmp_path
    monkeypatch.chdir(cwd)
    assert default_week_folder(3).resolve() == (tmp_path / expected).resolve()


def test_the_week_folder_wins_over_the_checkout_layout(tmp_path: Path) -> None:
    """./week3 before ./assignments/week3, and a folder named week4 is not week 3's."""
    (tmp_path / "week3").mkdir()
    (tmp_path / "assignments/week3").mkdir(parents=True)
    assert default_week_folder(3, tmp_path) == tmp_path / "week3"
    (tmp_path / "week4").mkdir()
    with pytest.raises(WeekFolderNotFound):
        default_week_folder(3, tmp_path / "week4")


def test_a_given_path_is_used_as_it_is(tmp_path: Path) -> None:
    assert week_folder(3, tmp_path / "anything") == tmp_path / "anything"


def test_no_week_folder_is_a_clear_message_in_all_three_commands(tmp_path: Path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    assert grade_main(["week3"]) == 2
    assert simiam_main(["run", "week3"]) == 2
    (tmp_path / "w2").mkdir()
    assert simiam_main(["migrate", "week3", "--from", "w2"]) == 2
    err = capsys.readouterr().err
    for command in ("grade:", "simiam run:", "simiam migrate:"):
        line = next(ln for ln in err.splitlines() if ln.startswith(command))
        assert "no week3 folder here" in line and "./week3" in line and "./assignments/week3" in line


def test_solutions_outside_the_checkout_says_so(tmp_path: Path, monkeypatch, capsys) -> None:
    monkeypatch.setattr(folders, "CHECKOUT", tmp_path)
    assert grade_main(["week3", "--solutions"]) == 2
    assert simiam_main(["run", "week3", "--solutions"]) == 2
    err = capsys.readouterr().err
    assert err.count("--solutions needs the course checkout") == 2


def test_run_and_migrate_from_inside_a_course_folder(tmp_path: Path, monkeypatch, capsys) -> None:
    """A student's course folder holding week2 and week3 (no checkout): both commands find them."""
    shutil.copytree(ROOT / "solutions/week2", tmp_path / "week2")
    shutil.copytree(ROOT / "assignments/week3", tmp_path / "week3")
    monkeypatch.chdir(tmp_path)
    assert simiam_main(["migrate", "week3", "--from", "week2"]) == 0
    # the folders as the student typed them (issue 23: no absolute paths when there is nothing to carry)
    assert "simiam migrate week3: from week2 into week3\n" in capsys.readouterr().out
    monkeypatch.chdir(tmp_path / "week3")
    assert simiam_main(["run", "week3", "--seconds", "0.5", "--out", str(tmp_path / "runs")]) == 0
    assert f"with {tmp_path / 'week3'}" in capsys.readouterr().out


def test_instructor_tooling_outside_the_checkout_says_so(tmp_path: Path, monkeypatch, capsys) -> None:
    """A student package holds no reference controllers: `simiam bench` exits 2 and says why."""
    monkeypatch.setattr(folders, "INSTRUCTOR_TOOLS", tmp_path / "instructor_tools")
    assert simiam_main(["bench", "--seconds", "0.1"]) == 2
    assert "instructor tooling in the course checkout" in capsys.readouterr().err


def test_the_hidden_set_lives_with_the_instructor_tools(monkeypatch) -> None:
    from grader.hidden import hidden_dir, load_hidden

    monkeypatch.delenv("SIMIAM_HIDDEN", raising=False)
    assert hidden_dir() == ROOT / "instructor_tools" / "hidden"
    assert load_hidden(4)["variants"]
    # nothing hidden left inside the grader package: its only JSON are the visible checks' expected values
    # and the practice sets students are meant to have (none of their variants a hidden one:
    # tests/grader/test_practice.py), and no hidden set's text is among them
    expected, practice = ROOT / "grader" / "checks" / "expected", ROOT / "grader" / "practice"
    shipped = list((ROOT / "grader").rglob("*.json"))
    assert not [p for p in shipped if p.parent not in (expected, practice)]
    assert not [p for p in expected.glob("*.json") if "variants" in p.read_text()]
    hidden = {p.read_text() for p in hidden_dir().glob("*.json")}
    assert len(hidden) >= 4 and not [p for p in shipped if p.read_text() in hidden]
