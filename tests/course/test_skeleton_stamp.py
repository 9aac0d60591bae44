"""The skeletons' stamp (simiam/course/skeleton_stamp.py): the grader's cheap check that the packaged
skeletons are still what `python -m simiam.course.stubs` makes from solutions/. It may only ever say "up to
date" when they are: every other case falls back to regenerating, which names the stale files."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from grader import grading
from simiam.course import skeleton_stamp, stubs

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def fresh_check():
    grading._skeletons_out_of_date.cache_clear()
    yield
    grading._skeletons_out_of_date.cache_clear()


def _checkout(tmp_path: Path) -> tuple[Path, Path]:
    """A copy of solutions/ and of the packaged skeletons (with their stamp) laid out as in the repo."""
    fake = tmp_path / "checkout"
    shutil.copytree(ROOT / "solutions", fake / "solutions", ignore=shutil.ignore_patterns("__pycache__"))
    skeletons = fake / "simiam" / "course" / "skeletons"
    shutil.copytree(skeleton_stamp.SKELETONS, skeletons, ignore=shutil.ignore_patterns("__pycache__"))
    return fake, skeletons


def test_the_committed_stamp_matches_the_solutions_and_skeletons():
    assert skeleton_stamp.up_to_date(ROOT / "solutions")
    assert str(skeleton_stamp.STAMP.relative_to(ROOT)) in stubs.generate().files  # drift-tested with the rest


def test_with_a_matching_stamp_the_grader_does_not_regenerate(monkeypatch, fresh_check):
    def regenerate(*_args):
        raise AssertionError("regenerated although the stamp matched")

    monkeypatch.setattr(stubs, "generate", regenerate)
    assert grading._skeletons_out_of_date() == ()


def test_a_hand_edited_skeleton_is_caught_and_named(tmp_path, monkeypatch, fresh_check):
    """Solutions unchanged, a skeleton edited inside a block: the stamp no longer matches, the full check
    names the file and grading refuses (a stamp of the inputs alone would have passed it)."""
    fake, skeletons = _checkout(tmp_path)
    edited = skeletons / "week3" / "go_to_goal.py"
    edited.write_text(edited.read_text() + "\nprint('hand edit')\n")
    assert not skeleton_stamp.up_to_date(fake / "solutions", skeletons)
    monkeypatch.setattr(grading, "ROOT", fake)
    monkeypatch.setattr(skeleton_stamp, "SKELETONS", skeletons)
    monkeypatch.setattr(stubs, "SKELETONS", skeletons)
    stale = r"skeletons/week3/go_to_goal.py.*simiam.course.stubs"
    with pytest.raises(grading.CourseFilesMissing, match=stale):
        grading.pristine_stubs(3, tmp_path / "splice")


@pytest.mark.parametrize("change", ["inside a block", "outside a block", "a new file", "a stamp removed"])
def test_any_change_to_the_inputs_misses_the_stamp(tmp_path, change):
    fake, skeletons = _checkout(tmp_path)
    sol = fake / "solutions" / "week3" / "go_to_goal.py"
    if change == "inside a block":
        sol.write_text(sol.read_text().replace("e_I = self.E_k + e_k * dt",
                                               "e_I = self.E_k + dt * e_k"))
    elif change == "outside a block":
        sol.write_text(sol.read_text().replace("self.E_k = 0", "self.E_k = 5"))
    elif change == "a new file":
        (fake / "solutions" / "week3" / "helper.py").write_text("x = 1\n")
    else:
        (skeletons / "stamp.json").unlink()
    assert sol.read_text() != (ROOT / "solutions/week3/go_to_goal.py").read_text() or change in (
        "a new file", "a stamp removed")
    assert skeleton_stamp.up_to_date(ROOT / "solutions", skeleton_stamp.SKELETONS)
    assert not skeleton_stamp.up_to_date(fake / "solutions", skeletons)


def test_a_solution_edit_that_changes_no_skeleton_still_grades(tmp_path, monkeypatch, fresh_check):
    """The stamp misses, the full regeneration finds every skeleton as it is: grading goes on."""
    fake, skeletons = _checkout(tmp_path)
    sol = fake / "solutions" / "week3" / "go_to_goal.py"
    sol.write_text(sol.read_text().replace("e_I = self.E_k + e_k * dt", "e_I = self.E_k + dt * e_k"))
    monkeypatch.setattr(grading, "ROOT", fake)
    monkeypatch.setattr(skeleton_stamp, "SKELETONS", skeletons)
    monkeypatch.setattr(stubs, "SKELETONS", skeletons)
    assert grading._skeletons_out_of_date() == ()
    assert (grading.pristine_stubs(3, tmp_path / "splice") / "go_to_goal.py").is_file()
