"""The grading engine around the checks: replay cases, feedback wording, load failures, result fields."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

from grader.cli import main as grade_main
from grader.grading import grade_submission
from grader.properties import format_case, parse_case

ROOT = Path(__file__).resolve().parents[2]


def test_case_text_round_trips() -> None:
    case = {"v": 0.1, "w": -2.0, "steps": [[1, 0], [2, -1]], "start": [0.0, 0.5, -3.14]}
    assert parse_case(format_case(case)) == case
    assert parse_case("v=0.1, w=\u22122.0") == {"v": 0.1, "w": -2.0}


def test_failing_property_names_the_case_and_replays_it(tmp_path: Path) -> None:
    folder = tmp_path / "week2"
    shutil.copytree(ROOT / "solutions" / "week2", folder)
    drive = folder / "differential_drive.py"
    drive.write_text(drive.read_text().replace("(2 * v + w * L) / (2 * R)", "(2 * v + w * L) / R"))
    result = grade_submission(2, folder, seed=5, only="week2.uni_to_diff.round_trip")
    check = result["checks"][0]
    assert check["status"] == "failed" and check["points"] == 0
    assert check["message"].startswith("with v = ") and "your vel_r was" in check["message"]
    replay = check["details"]["replay"]
    assert "--check week2.uni_to_diff.round_trip --case '" in replay
    case = parse_case(replay.split("--case ")[1].strip("'"))
    again = grade_submission(2, folder, seed=5, only="week2.uni_to_diff.round_trip", case=case)
    assert again["checks"][0]["status"] == "failed"
    assert again["checks"][0]["message"] == check["message"]


def test_syntax_error_fails_only_the_checks_that_need_the_file(tmp_path: Path) -> None:
    folder = tmp_path / "week3"
    shutil.copytree(ROOT / "solutions" / "week3", folder)
    goal = folder / "go_to_goal.py"
    goal.write_text(goal.read_text().replace("        u_x = x_g - x\n", "        u_x = = x_g - x\n"))
    result = grade_submission(3, folder, seed=1)
    assert result["status"] == "graded"
    by_id = {c["id"]: c for c in result["checks"]}
    assert by_id["week3.pid.proportional"]["status"] == "error"
    assert "go_to_goal.py:" in by_id["week3.pid.proportional"]["message"]
    assert by_id["week3.ensure_w.keeps_w"]["status"] == "passed"


def test_nothing_loadable_is_invalid(tmp_path: Path) -> None:
    folder = tmp_path / "week2"
    shutil.copytree(ROOT / "assignments" / "week2", folder)
    sup = folder / "differential_drive.py"
    sup.write_text("import sys\nsys.exit(3)\n" + sup.read_text())  # outside the blocks: not run
    result = grade_submission(2, folder, seed=1, only="week2.uni_to_diff.straight")
    assert result["status"] == "graded"  # the splice dropped the edit outside the blocks
    assert any("outside the code blocks" in n for n in result["notices"])
    missing = grade_submission(2, tmp_path / "nowhere", seed=1)
    assert missing["status"] == "invalid" and "no such folder" in missing["message"]


def test_result_records_version_hash_seed_and_isolation(tmp_path: Path) -> None:
    code = grade_main(["week1", str(ROOT / "assignments" / "week1"), "--out", str(tmp_path), "--seed", "9"])
    assert code == 0
    result = json.loads((tmp_path / "week1.json").read_text())
    assert result["seed"] == 9 and result["check_set_hash"] in result["grader_version"]
    assert result["isolation"] in ("bwrap", "subprocess")
    assert grade_main(["week99"]) == 2  # no such week
    assert grade_main(["week2", str(tmp_path / "missing")]) == 2


def test_no_folder_here_tells_the_student_what_to_do(tmp_path: Path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    assert grade_main(["week3"]) == 2
    err = capsys.readouterr().err
    assert "go into your week3 folder (or the folder holding it)" in err and "grade week3 PATH" in err


def test_nan_and_exceptions_get_clear_messages(tmp_path: Path) -> None:
    folder = tmp_path / "week2"
    shutil.copytree(ROOT / "solutions" / "week2", folder)
    drive = folder / "differential_drive.py"
    text = drive.read_text()
    drive.write_text(text.replace("    vel_l = (2 * v - w * L) / (2 * R)\n", "    vel_l = float('nan')\n"))
    nan = grade_submission(2, folder, seed=1, only="week2.uni_to_diff.straight")["checks"][0]
    assert nan["status"] == "failed" and "was NaN, expected a finite number" in nan["message"]
    drive.write_text(text.replace("    vel_l = (2 * v - w * L) / (2 * R)\n", "    vel_l = 1 / 0\n"))
    crash = grade_submission(2, folder, seed=1, only="week2.uni_to_diff.straight")["checks"][0]
    assert crash["status"] == "failed"
    assert "ZeroDivisionError" in crash["message"] and "differential_drive.py:" in crash["message"]
    assert crash["message"].startswith("with v = ")


def test_a_timeout_in_the_middle_of_a_property_search_is_reported_as_a_timeout() -> None:
    """An infinite loop stops the search at once and says so, whatever Hypothesis makes of the aborted
    search (it used to be reported as 'your code gave different answers to the same input')."""
    from hypothesis import strategies as st

    from grader.checks import Context
    from grader.properties import run_property
    from grader.sandbox.errors import StudentTimeout

    calls = []

    def case(ctx: Context, x: float) -> None:
        calls.append(x)
        if len(calls) == 1:  # the worker is restarted after a kill, so later calls may answer
            raise StudentTimeout("no answer within 2 s, the time limit per call")

    outcome = run_property(Context(week=3, seed=1, session=None), "week3.pid.integral",
                           {"x": st.floats(-1, 1)}, case)
    assert outcome.fraction == 0.0 and outcome.status == "timeout"
    assert outcome.message == ("your code did not answer in time: "
                               "no answer within 2 s, the time limit per call")


def test_an_edited_assignments_folder_is_never_taken_as_the_pristine_stubs(
        tmp_path: Path, monkeypatch) -> None:
    """Issue 11: in a checkout without solutions/, the student's own assignments/week3 (edited outside the
    blocks) used to be the "pristine" stub, so the edit ran. The packaged skeletons are used instead."""
    from grader import grading

    fake = tmp_path / "checkout"
    shutil.copytree(ROOT / "assignments" / "week3", fake / "assignments" / "week3")
    edited = fake / "assignments" / "week3" / "go_to_goal.py"
    edited.write_text(edited.read_text().replace("self.E_k = 0", "self.E_k = 7"))
    monkeypatch.setattr(grading, "ROOT", fake)
    stubs = grading.pristine_stubs(3, tmp_path / "splice")
    assert "self.E_k = 7" not in (stubs / "go_to_goal.py").read_text()
    assert (stubs / "go_to_goal.py").read_text() == (ROOT / "assignments/week3/go_to_goal.py").read_text()
    result = grade_submission(3, fake / "assignments" / "week3", seed=1, only="week3.pid.integral")
    assert any("go_to_goal.py" in n and "self.E_k = 7" in n for n in result["notices"])


def test_a_grader_installed_without_its_skeletons_refuses_instead_of_scoring_zero(
        tmp_path: Path, monkeypatch, capsys) -> None:
    """A broken build without the skeleton data: splicing into nothing would give every student 0."""
    import pytest

    from grader import grading
    from simiam.course import skeletons

    monkeypatch.setattr(skeletons, "__name__", "simiam.course")  # resources of a package without weekN/
    with pytest.raises(grading.CourseFilesMissing, match="skeleton files of week 3 are missing"):
        grade_submission(3, ROOT / "solutions" / "week3", seed=1)
    assert grade_main(["week3", str(ROOT / "solutions" / "week3"), "--out", str(tmp_path / "r")]) == 2
    assert "skeleton files of week 3 are missing" in capsys.readouterr().err


def test_skeletons_out_of_date_with_the_solutions_refuse(tmp_path: Path, monkeypatch) -> None:
    """In a checkout, solutions/ changed outside a block without regenerating: grading stops and says how."""
    import pytest

    from grader import grading

    fake = tmp_path / "checkout"
    shutil.copytree(ROOT / "solutions", fake / "solutions")
    sol = fake / "solutions" / "week3" / "go_to_goal.py"
    sol.write_text(sol.read_text().replace("self.E_k = 0", "self.E_k = 5"))
    monkeypatch.setattr(grading, "ROOT", fake)
    grading._skeletons_out_of_date.cache_clear()
    try:
        with pytest.raises(grading.CourseFilesMissing, match="python -m simiam.course.stubs"):
            grading.pristine_stubs(3, tmp_path / "splice")
    finally:
        grading._skeletons_out_of_date.cache_clear()


def test_the_worker_starts_before_the_weeks_checks_are_imported(tmp_path: Path) -> None:
    """The worker boots (0.15-0.3 s) while the grading process imports the checks and the report; and a
    week-3 grading that passes never imports numpy, shapely or hypothesis (0.2-0.5 s of CPU)."""
    code = f"""
import sys
from pathlib import Path
from grader.sandbox.session import StudentSession
start = StudentSession.start
seen = []
def recording(self):
    seen.append(sorted(m for m in ("grader.checks.week3", "grader.report.html", "numpy") if m in sys.modules))
    start(self)
StudentSession.start = recording
from grader.grading import grade_submission
result = grade_submission(3, Path({str(ROOT / "solutions" / "week3")!r}), seed=1, out_dir={str(tmp_path)!r})
assert result["score"] == result["max_score"], result["message"]
print(seen)
print(sorted(m for m in ("numpy", "shapely", "hypothesis") if m in sys.modules))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:2] == ["[[]]", "[]"], out.stdout
    assert (tmp_path / "week3.html").is_file()


def test_a_worker_that_cannot_even_be_spawned_is_a_grader_error_not_a_crash(monkeypatch) -> None:
    """The worker is spawned before the checks run (StudentSession.start); a failure there (here the
    library copy hits a full disk) is raised by the first call and reported like any grader fault."""
    import grader.sandbox.isolation as isolation

    def full_disk(mode: str, beside: Path) -> Path:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(isolation, "worker_library", full_disk)
    result = grade_submission(3, ROOT / "solutions" / "week3", seed=1)
    assert result["status"] == "invalid" and result["score"] == 0
    assert "bug in the grader" in result["message"] and "OSError" in result["message"]
