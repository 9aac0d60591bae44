"""`simiam run` with student code that misbehaves: an endless loop is stopped with the location message
`grade` gives, any exception the student's code raises (sys.exit included) exits non-zero, and edits outside
the code blocks are listed as `grade` lists them (run here, ignored by grade)."""

from __future__ import annotations

import argparse
from pathlib import Path

import mistakes

from grader.grading import grade_submission
from grader.sandbox.limits import Limits
from simiam import run
from simiam.run import main


def _args(folder: Path, out: Path, seconds: float = 3.0) -> argparse.Namespace:
    return argparse.Namespace(week="week3", path=str(folder), solutions=False, seconds=seconds, dt=0.033,
                              out=str(out), world=None)


def _line(folder: Path, mark: str) -> int:
    return next(i for i, t in enumerate((folder / "go_to_goal.py").read_text().splitlines(), 1) if mark in t)


def test_an_endless_loop_is_stopped_where_grade_says_it_is(tmp_path: Path, capsys, monkeypatch) -> None:
    folder = mistakes.build("stuck", "week3_endless_loop", tmp_path, 3, "week3")
    monkeypatch.setattr(run, "STEP_SECONDS", 0.5)
    assert main(_args(folder, tmp_path / "out")) == 1
    err = capsys.readouterr().err
    line = _line(folder, "# STUCK")
    where = (f"it was still running at go_to_goal.py:{line} in GoToGoal.execute "
             "(an endless loop or a long wait?)")
    assert "your code did not answer in time: no answer within 0.5 s, the time limit per step" in err
    assert where in err
    # the loop is at the first step: only loading answers within the 0.5 s (ms; test_timeout_location)
    graded = grade_submission(3, folder, seed=1, only="week3.go_to_goal.reach_goals",
                              limits=Limits(call_seconds=0.5, total_seconds=20.0))
    assert where in graded["checks"][0]["message"]
    assert (tmp_path / "out" / "week3.json").is_file()


def test_student_code_that_exits_makes_the_run_fail(tmp_path: Path, capsys) -> None:
    folder = mistakes.build("submissions", "week3_exit_when_close", tmp_path, 3, "week3")
    assert main(_args(folder, tmp_path / "out", seconds=10.0)) == 1
    err = capsys.readouterr().err
    line = _line(folder, "WRONG")
    assert f"go_to_goal.py:{line}: your code called sys.exit() (at t = " in err


def test_edits_outside_the_blocks_are_warned_about(tmp_path: Path, capsys) -> None:
    folder = mistakes.build("submissions", "week3_edit_outside_blocks", tmp_path, 3, "week3")
    assert main(_args(folder, tmp_path / "out", seconds=0.5)) == 0
    err = capsys.readouterr().err
    assert "warning: qb_supervisor.py" in err and "grade runs only the code blocks" in err
    graded = grade_submission(3, folder, seed=1, only="week3.pid.memory")
    assert any(n.startswith("qb_supervisor.py") for n in graded["notices"])


def test_a_missing_shipped_file_is_filled_in_and_named(tmp_path: Path, capsys) -> None:
    # week 3 ships differential_drive.py and go_to_angle.py complete: a folder without them still runs
    # (with the versions the course ships, from the checkout's solutions/), as grade grades it
    folder = mistakes.build("submissions", "week3_edit_outside_blocks", tmp_path, 3, "week3")
    (folder / "differential_drive.py").unlink()
    (folder / "go_to_angle.py").unlink()
    assert main(_args(folder, tmp_path / "out", seconds=0.5)) == 0
    err = capsys.readouterr().err
    assert "warning: differential_drive.py is missing from your submission" in err
    assert "warning: go_to_angle.py is missing from your submission" in err
    assert not (folder / "differential_drive.py").exists()   # the student's folder is not written to


def test_a_missing_file_to_write_is_still_a_load_error(tmp_path: Path, capsys) -> None:
    folder = mistakes.build("submissions", "week3_edit_outside_blocks", tmp_path, 3, "week3")
    (folder / "go_to_goal.py").unlink()
    assert main(_args(folder, tmp_path / "out", seconds=0.5)) == 1
    assert "could not be loaded" in capsys.readouterr().err


def test_an_error_at_the_first_step_is_said_first_and_not_contradicted(tmp_path: Path) -> None:
    """A NameError at the first step: `simiam run` printed "0.00 s simulated, 0 steps ... the robot never
    stopped" and only then the error. The error now comes first (in the terminal's order: one stream), and
    the summary says the error stopped the robot."""
    import shutil
    import subprocess
    import sys

    folder = tmp_path / "week3"
    shutil.copytree(Path(__file__).resolve().parents[2] / "solutions" / "week3", folder)
    source = (folder / "go_to_goal.py").read_text().splitlines()
    execute = next(i for i, t in enumerate(source) if "def execute(" in t)
    at = next(i for i, t in enumerate(source) if i > execute and "# START CODE BLOCK" in t)
    source.insert(at + 1, "        undefined_name_here  # NAME")  # inside a block: no warning comes first
    (folder / "go_to_goal.py").write_text("\n".join(source) + "\n")
    simiam = str(Path(sys.executable).parent / "simiam")
    proc = subprocess.run([simiam, "run", "week3", str(folder), "--out", str(tmp_path / "runs")],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert proc.returncode == 1
    lines = [ln for ln in proc.stdout.splitlines() if ln.strip()]
    line = _line(folder, "# NAME")
    assert lines[0].startswith(f"go_to_goal.py:{line}: NameError: name 'undefined_name_here' is not defined")
    assert "never stopped" not in proc.stdout and "was stopped by your code's error at t = " in proc.stdout
