"""`simiam run`: runs the solutions and writes trace + replay; reports load and runtime errors as
file:line and exits 1 (wrong submissions from tests/data/submissions/)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import mistakes
import pytest

from simiam.run import main

ROOT = Path(__file__).resolve().parents[2]


def _args(week: str, out: Path, path: str | None = None, solutions: bool = False, seconds=None, dt=0.033):
    return argparse.Namespace(week=week, path=path, solutions=solutions, seconds=seconds, dt=dt,
                              out=str(out), world=None)


def _folder(tmp_path: Path, week: int, mutant: str) -> Path:
    return mistakes.build("submissions", mutant, tmp_path, week)


def test_solutions_run_writes_trace_replay_and_summary(tmp_path, capsys):
    assert main(_args("week3", tmp_path, solutions=True)) == 0
    out = capsys.readouterr().out
    assert "Goal (-1, 1) reached" in out and "No collision" in out
    trace = json.loads((tmp_path / "week3.json").read_text())
    assert trace["format"] == "simiam-trace/1" and trace["goal"] == [-1.0, 1.0]
    assert trace["steps"]["state"][-1] == "stop"
    assert (tmp_path / "week3.csv").is_file() and (tmp_path / "week3.html").is_file()


def test_week5_blending_reports_its_goal(tmp_path, capsys):
    """Week 5 starts in ao_and_gtg, which drives to the goal too: the summary says whether it got there."""
    assert main(_args("week5", tmp_path, solutions=True, seconds=12.0)) == 0
    out = capsys.readouterr().out
    assert "Goal (1, 1) reached: the robot stopped at t = 9.31 s" in out and "No collision" in out


def test_a_submission_that_does_not_load_exits_1_with_file_and_line(tmp_path, capsys):
    folder = _folder(tmp_path, 3, "loader_syntax_error")
    assert main(_args("week3", tmp_path / "out", path=str(folder))) == 1
    err = capsys.readouterr().err
    line = next(i for i, t in enumerate((folder / "go_to_goal.py").read_text().splitlines(), 1)
                if "atan2(u_y, u_x" in t)
    assert f"go_to_goal.py:{line}: syntax error" in err
    assert not (tmp_path / "out").exists()


def test_an_exception_during_the_run_exits_1_and_keeps_the_trace(tmp_path, capsys):
    folder = _folder(tmp_path, 3, "week3_runtime_error")
    assert main(_args("week3", tmp_path / "out", path=str(folder))) == 1
    err = capsys.readouterr().err
    line = next(i for i, t in enumerate((folder / "go_to_goal.py").read_text().splitlines(), 1)
                if "(dt - dt)" in t)
    assert f"go_to_goal.py:{line}: ZeroDivisionError" in err
    assert (tmp_path / "out/week3.json").is_file()


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        ({"week": "week9"}, "no such week"),
        ({"week": "week3", "dt": -1.0}, "--dt"),
        ({"week": "week3", "path": "/nonexistent/folder"}, "no such folder"),
        ({"week": "week3", "seconds": 1e9, "dt": 1e-300}, "steps; at most"),
    ],
)
def test_bad_arguments_exit_2(tmp_path, capsys, argv, message):
    args = _args(argv["week"], tmp_path, path=argv.get("path"), dt=argv.get("dt", 0.033),
                 seconds=argv.get("seconds"))
    assert main(args) == 2
    assert message in capsys.readouterr().err


def test_an_unwritable_output_folder_exits_2(tmp_path, capsys):
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    assert main(_args("week1", blocker / "out", solutions=True, seconds=0.1)) == 2
    assert "cannot write the trace" in capsys.readouterr().err
