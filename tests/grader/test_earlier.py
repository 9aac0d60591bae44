"""Week-5 runs use the course's versions of earlier weeks' parts (grader.earlier): a week-4 mistake does not
sink week 5. The course's versions come from solutions/ in a checkout, else from $SIMIAM_HANDOUT (a
bundle's handout); with neither the student's own code runs and the check says so."""

from __future__ import annotations

from pathlib import Path

import pytest
from wrong_submissions import ROOT, build

import grader.earlier as earlier
from grader.grading import grade_submission
from simiam.course.blocks import find_blocks

MISTAKE = "good_week5_week4_u_ao_reversed"  # a week-4 mistake in an otherwise correct week-5 folder


def _bodies(folder: Path, name: str) -> dict:
    return {b.key: b.body for b in find_blocks((folder / name).read_text(), name)}


def test_the_folder_takes_this_weeks_blocks_from_the_student_and_the_rest_from_the_course(tmp_path):
    student = build(MISTAKE, tmp_path)
    (student / "ao_and_gtg.py").write_text((student / "ao_and_gtg.py").read_text().replace(
        "alpha = 0.25", "alpha = 0.4"))
    folder = earlier.reference_folder(5, student, tmp_path / "earlier")
    assert folder is not None
    course = ROOT / "solutions/week5"
    assert _bodies(folder, "avoid_obstacles.py") == _bodies(course, "avoid_obstacles.py")  # course's week 4
    assert "alpha = 0.4" in _bodies(folder, "ao_and_gtg.py")[("AOandGTG.execute", 1)]       # student's week 5
    assert _bodies(folder, "qb_supervisor.py") == _bodies(student, "qb_supervisor.py")


def test_a_bundle_takes_the_course_versions_from_its_handout(tmp_path, monkeypatch):
    monkeypatch.setattr(earlier, "ROOT", tmp_path / "no-checkout")
    monkeypatch.setenv("SIMIAM_HANDOUT", str(ROOT / "assignments/week5"))
    folder = earlier.reference_folder(5, build(MISTAKE, tmp_path), tmp_path / "earlier")
    assert folder is not None
    assert _bodies(folder, "avoid_obstacles.py") == _bodies(ROOT / "solutions/week5", "avoid_obstacles.py")


def test_without_the_course_versions_there_is_no_folder(tmp_path, monkeypatch):
    monkeypatch.setattr(earlier, "ROOT", tmp_path / "no-checkout")
    monkeypatch.delenv("SIMIAM_HANDOUT", raising=False)
    assert earlier.reference_folder(5, build(MISTAKE, tmp_path), tmp_path / "earlier") is None


@pytest.mark.parametrize("course_versions", [True, False])
def test_a_week4_mistake_costs_week5_runs_only_without_the_course_versions(tmp_path, monkeypatch,
                                                                           course_versions):
    if not course_versions:  # the wrong version of the mechanism: the student's own earlier code runs
        monkeypatch.setattr(earlier, "reference_folder", lambda *args: None)
    result = grade_submission(5, build(MISTAKE, tmp_path), seed=2014, only="week5.blending.reach_goal")
    (check,) = result["checks"]
    if course_versions:
        assert check["status"] == "passed" and "Note" not in check["message"]
    else:
        assert check["status"] == "failed" and "collided" in check["message"]
        assert "your own code for earlier weeks' parts" in check["message"]


def test_a_bundle_grades_week5_runs_with_its_handout(tmp_path, monkeypatch):
    """Gradescope and PrairieLearn grade through official.grade_upload with the handout they carry: with no
    solutions/ at hand, the runs still use the course's earlier parts (from the handout)."""
    from grader.platforms import official

    monkeypatch.setattr(earlier, "ROOT", tmp_path / "no-checkout")  # as in a bundle: no solutions/
    monkeypatch.delenv("SIMIAM_HANDOUT", raising=False)  # grade_upload sets both; restored after the test
    monkeypatch.setenv("SIMIAM_HIDDEN", str(ROOT / "instructor_tools/hidden"))
    secret = official.Secret(week=5, seed=2014, hidden_dir=ROOT / "instructor_tools/hidden")
    result = official.grade_upload(build(MISTAKE, tmp_path), secret, fill_from=ROOT / "assignments/week5")
    runs = {c["id"]: c for c in result["checks"] if c["kind"] == "scenario"}
    assert runs and all(c["status"] == "passed" for c in runs.values()), runs
    assert all("Note" not in c["message"] for c in runs.values())


@pytest.mark.parametrize("label, second_worker", [("solutions/week5", False), (MISTAKE, True)])
def test_a_second_worker_only_where_the_earlier_blocks_differ_from_the_courses(tmp_path, monkeypatch, label,
                                                                               second_worker):
    """The course's earlier blocks in the student's files already (as the handout ships them): the runs use
    the worker at hand, with the same code; a second sandbox start (~0.1 CPU-s) only where they differ."""
    import grader.grading as grading

    opened = []
    real = grading._open_session
    monkeypatch.setattr(grading, "_open_session", lambda job, folder, others: opened.append(folder)
                        or real(job, folder, others))
    folder = ROOT / label if "/" in label else build(label, tmp_path)
    result = grade_submission(5, folder, seed=2014, only="week5.blending.reach_goal")
    (check,) = result["checks"]
    assert check["status"] == "passed" and "Note" not in check["message"], check["message"]
    assert len(opened) == int(second_worker)


def test_same_files_compares_names_and_bytes(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    for folder in (a, b):
        folder.mkdir()
        (folder / "x.py").write_text("x = 1\n")
    assert earlier.same_files(a, b)
    (b / "x.py").write_text("x = 2\n")
    assert not earlier.same_files(a, b)  # other bytes
    (b / "x.py").write_text("x = 1\n")
    (b / "y.py").write_text("")
    assert not earlier.same_files(a, b)  # a file more
    (b / "y.py").unlink()
    (b / "x.py").unlink()
    (b / "x.py").symlink_to(a / "x.py")
    assert not earlier.same_files(a, b)  # a link is not a file of the folder
