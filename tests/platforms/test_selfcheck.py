"""`grade selfcheck` passes on the course as it is and fails, naming the problem, when a solution loses
points, a stub scores, or a wrong version does not lose exactly its aimed checks; the CI workflow for an
instructor's repository runs it."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest
import yaml
from mistakes import DATA, ROOT, build, read_mistake

from grader.cli import main
from grader.platforms.selfcheck import Expectation, check_one, full_marks, run_selfcheck, zero_points

sys.path.insert(0, str(ROOT / "tests" / "grader"))
from test_checks_fail import EXPECTED_FAILURES  # noqa: E402


@pytest.mark.slow
def test_the_course_passes_its_selfcheck_for_week3():
    lines: list[str] = []
    assert run_selfcheck(ROOT, [3], out=lines.append) == 0
    assert lines[-1] == "selfcheck: all expectations held"
    assert any(ln.startswith("ok    solutions week3 (hidden checks included)") for ln in lines)
    assert any(ln.startswith("ok    stubs week3 (zero on every coded part)") for ln in lines)
    week3 = [p for p in (DATA / "wrong").glob("*.patch") if read_mistake(p).week == 3]
    assert len(week3) >= 7 and sum(ln.startswith("ok    wrong ") for ln in lines) == len(week3)
    # the margins: every figure of the reference's scenario checks with what it has to spare, and the figures
    # of a caught wrong version past their limits
    assert any(ln.startswith("        margin week3.go_to_goal.reach_goals: clearance ") and "to spare" in ln
               for ln in lines)
    assert any(ln.startswith("        margin week3.pid.settle_time: settle time ") for ln in lines)
    weak = lines.index(next(ln for ln in lines if ln.startswith("ok    wrong week3_weak_gains ")))
    assert [ln.split(":")[0] for ln in lines[weak + 1:weak + 3]] == [
        "        margin week3.pid.settle_time", "        margin week3.pid.overshoot"]
    assert all("past it" in ln or "ended without it" in ln for ln in lines[weak + 1:weak + 3])


@pytest.mark.slow
def test_wrong_versions_with_a_wrong_aim_no_aim_or_a_stale_patch_fail_it(tmp_path: Path):
    wrong = tmp_path / "wrong"
    wrong.mkdir()
    text = (DATA / "wrong" / "week3_no_wrap.patch").read_text().splitlines(keepends=True)
    (wrong / "misaimed.patch").write_text("".join([text[0], "# aims: week3.pid.integral\n", *text[2:]]))
    (wrong / "unaimed.patch").write_text("".join([text[0], *text[2:]]))
    stale = "".join(text).replace("-        e_k = math.atan2", "-        e_k = atan2")
    (wrong / "stale.patch").write_text(stale)
    lines: list[str] = []
    assert run_selfcheck(ROOT, [3], wrong=wrong, out=lines.append) == 1
    text = "\n".join(lines)
    assert "FAIL  wrong misaimed (loses week3.pid.integral): keeps the points of week3.pid.integral it " \
           "aims at; also loses week3.go_to_goal.error_wrap" in text
    assert "FAIL  wrong unaimed: no '# aims:' line" in text
    assert "FAIL  wrong stale: " in text and "does not apply" in text
    assert lines[-1] == "selfcheck: 3 failed"


def test_a_solution_that_loses_points_or_a_stub_that_scores_fails(tmp_path: Path):
    lines: list[str] = []
    solution = tmp_path / "solution"
    shutil.copytree(ROOT / "solutions" / "week2", solution)
    wrong = build("wrong", "week2_full_L", tmp_path)
    assert check_one(Expectation("solutions week2", 2, wrong, False, full_marks), 2014, lines.append) == 1
    assert check_one(Expectation("stubs week2", 2, solution, False, zero_points), 2014, lines.append) == 1
    assert lines[0].startswith("FAIL  solutions week2: lost week2.uni_to_diff.round_trip")
    assert lines[1].startswith("FAIL  stubs week2: the stub scores on ")


def test_every_kept_wrong_version_declares_its_aims():
    # the grader tests read EXPECTED_FAILURES from these lines: a patch without one would expect nothing
    unsaid = [p.name for p in sorted((DATA / "wrong").glob("*.patch")) if read_mistake(p).aims is None]
    assert unsaid == []
    assert len(EXPECTED_FAILURES) >= 30 and any(EXPECTED_FAILURES.values())


def test_selfcheck_refuses_a_course_the_grader_was_not_installed_from(tmp_path: Path, capsys):
    (tmp_path / "solutions" / "week1").mkdir(parents=True)
    assert main(["selfcheck", "--course", str(tmp_path)]) == 2
    assert "pip install -e" in capsys.readouterr().err


def test_the_ci_workflow_installs_the_checkout_and_runs_the_selfcheck():
    workflow = yaml.safe_load((ROOT / "docs" / "ci-selfcheck.yml").read_text())
    steps = workflow["jobs"]["selfcheck"]["steps"]
    runs = [s.get("run", "") for s in steps]
    assert any("pip install -e ." in r for r in runs)
    assert any(r.strip() == "grade selfcheck" for r in runs)
    assert any("simiam.course.stubs --check" in r for r in runs)
    assert any("grade handout" in r for r in runs)
    assert steps[0]["uses"].startswith("actions/checkout@")


def test_the_coverage_line_counts_what_each_check_catches_and_names_those_that_catch_none():
    """Issue 21: per week, how many kept wrong versions each check catches, and which catch none."""
    from grader.platforms.selfcheck import coverage

    line = coverage(7, [frozenset({"week7.sliding.sigma"}), frozenset({"week7.sliding.sigma",
                                                                      "week7.navigate.release_goal"}),
                        frozenset()])
    assert line.startswith("coverage week7 (3 kept wrong versions): week7.sliding.sigma 2, "
                           "week7.navigate.release_goal 1; caught by none: ")
    assert "week7.fsm.transitions" in line.split("caught by none: ")[1]
    assert "(hidden, not graded here: week7.navigate.other_goals)" in line
    every = coverage(7, [frozenset({c}) for c in ("week7.sliding.sigma", "week7.progress.made",
                                                  "week7.progress.point", "week7.fsm.transitions",
                                                  "week7.navigate.release_goal")])
    assert "every visible check catches one" in every
