"""What every bundle carries: a wheel built from a clean copy of the course (stale build/ output cannot sneak
an answer in; a wheel holding answers is named and refused), and a grading that gives the reference
solution full marks, else nothing is written."""

from __future__ import annotations

import shutil
import zipfile
from pathlib import Path

import pytest
from mistakes import ROOT

from grader.cli import main
from grader.platforms.wheel import _NOT_SOURCE, answers_in, build_wheel


def test_answers_in_a_wheel_are_named(tmp_path: Path):
    wheel = tmp_path / "simiam-0-py3-none-any.whl"
    with zipfile.ZipFile(wheel, "w") as archive:
        for name in ("grader/grading.py", "grader/hidden/week4.json", "instructor_tools/reference_brains.py",
                     "solutions/week3/go_to_goal.py", "simiam/course/skeletons/week3/go_to_goal.py"):
            archive.writestr(name, "x")
    assert answers_in(wheel) == ["grader/hidden/week4.json", "instructor_tools/reference_brains.py",
                                 "solutions/week3/go_to_goal.py"]


@pytest.mark.slow
def test_stale_build_output_in_the_checkout_does_not_reach_the_wheel(tmp_path: Path):
    course = tmp_path / "course"
    shutil.copytree(ROOT, course, ignore=shutil.ignore_patterns(*_NOT_SOURCE))
    stale = course / "build" / "lib" / "grader" / "hidden"
    stale.mkdir(parents=True)
    (stale / "week4.json").write_text('{"variants": []}')
    wheel = build_wheel(course, tmp_path / "dist")
    assert answers_in(wheel) == []
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
    assert "simiam/course/skeletons/week3/go_to_goal.py" in names and "grader/platforms/templates/" \
        "gradescope_setup.sh" in names


@pytest.mark.slow
def test_a_bundle_without_the_weeks_hidden_set_is_refused(tmp_path: Path, monkeypatch, capsys):
    monkeypatch.setenv("SIMIAM_HIDDEN", str(tmp_path / "no-hidden-set"))
    out = tmp_path / "autograder.zip"
    args = ["package", "gradescope", "week4", "--out", str(out), "--seed", "5", "--course", str(ROOT)]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "would not give solutions/week4 full marks" in err and "week4.avoid.other_starts" in err
    assert not out.exists()
