"""The wheel a bundle ships is built from a clean copy of the course (stale build/ output cannot sneak an
answer in), and a wheel or an installed package holding answers is named, so the bundle refuses it."""

from __future__ import annotations

import shutil
import zipfile
from pathlib import Path

import pytest
from mistakes import ROOT

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
