"""`simiam run`: runs the solutions and writes trace + replay; reports load and runtime errors as
file:line and exits 1 (wrong submissions from tests/data/submissions/)."""

from __future__ import annotations

import argparse
import json
import shutil
from dataclasses import replace
from pathlib import Path

import mistakes
import pytest

from simiam import run
from simiam.course.weeks import get_week
from simiam.laps import Gate
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
    assert "Laps" not in out  # week 3 declares no lap gate
    trace = json.loads((tmp_path / "week3.json").read_text())
    assert trace["format"] == "simiam-trace/1" and trace["goal"] == [-1.0, 1.0]
    assert trace["steps"]["state"][-1] == "stop"
    assert (tmp_path / "week3.csv").is_file() and (tmp_path / "week3.html").is_file()


def test_week6_prints_the_laps_through_its_gate(tmp_path, capsys):
    """Week 6 declares a lap gate: the summary counts the laps through it as grade does (the solution
    follows the wall on the left, round the L anticlockwise)."""
    assert main(_args("week6", tmp_path, solutions=True, dt=0.05)) == 0
    out = capsys.readouterr().out
    assert ("Laps: 3 through the gate (x = 0 from y = -1.4 to 0.2, crossed toward +x), the first completed "
            "at t = ") in out


def test_a_run_round_the_other_way_counts_its_laps_too(tmp_path, capsys):
    """The student picks the side in their __init__: on the right the robot goes round clockwise."""
    folder = tmp_path / "week6"
    shutil.copytree(ROOT / "solutions/week6", folder)
    supervisor = folder / "qb_supervisor.py"
    text = supervisor.read_text()
    assert 'self.fw_direction = "left"' in text
    supervisor.write_text(text.replace('self.fw_direction = "left"', 'self.fw_direction = "right"'))
    assert main(_args("week6", tmp_path / "out", path=str(folder), dt=0.05)) == 0
    out = capsys.readouterr().out
    assert "Laps: 3 through the gate (x = 0 from y = -1.4 to 0.2, crossed toward -x)" in out


def test_the_laps_line_follows_the_weeks_declaration(tmp_path, capsys, monkeypatch):
    """The line is there because a week declares a gate, not because it is week 6: week 3 given a gate
    on its way to the goal prints one lap; week 6 without one prints none."""
    week3, week6 = get_week(3), get_week(6)
    gated = {3: replace(week3, lap_gate=Gate(x=-0.5, y_low=-1.0, y_high=1.0, sign=-1)),
             6: replace(week6, lap_gate=None)}
    monkeypatch.setattr(run, "get_week", lambda week: gated[int(str(week).removeprefix("week"))])
    assert main(_args("week3", tmp_path, solutions=True)) == 0
    out = capsys.readouterr().out
    assert "Laps: 1 through the gate (x = -0.5 from y = -1 to 1, crossed toward -x), completed at t = " in out
    assert main(_args("week6", tmp_path, solutions=True, seconds=2.0, dt=0.05)) == 0
    assert "Laps" not in capsys.readouterr().out


def test_laps_are_counted_in_the_weeks_own_world_only(tmp_path, capsys):
    """A gate placed for the week-6 world says nothing about another world (--world); a copy of the
    week's own world file still counts."""
    from simiam.world import world_path

    args = _args("week6", tmp_path, solutions=True, seconds=2.0, dt=0.05)
    args.world = "final"  # (week 4's world is week 6's)
    assert main(args) == 0
    assert "Laps" not in capsys.readouterr().out
    shutil.copy(world_path("week6"), tmp_path / "mine.xml")
    args.world = str(tmp_path / "mine.xml")
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "Laps: 0 through the gate (x = 0 from y = -1.4 to 0.2, crossed toward +x)." in out


def test_week5_blending_reports_its_goal(tmp_path, capsys):
    """Week 5 starts in ao_and_gtg, which drives to the goal too: the summary says whether it got there."""
    assert main(_args("week5", tmp_path, solutions=True, seconds=12.0)) == 0
    out = capsys.readouterr().out
    assert ("Goal (1, 1) reached: the TRUE position came within 0.0492 m of it (d_stop = 0.05); the robot "
            "stopped at t = 9.31 s, 0.0492 m from it (its estimate 0.0484 m from it") in out
    assert "No collision" in out


def test_the_goal_line_says_reached_as_grade_does_with_the_digits_that_decide(tmp_path, capsys):
    """Issue 21: "not reached, 0.050 m (d_stop = 0.05)" beside "reached, 0.050 m". Reached is the TRUE
    position within d_stop at some step (as grade judges it), shown with four decimals, and the estimate
    the robot stopped by beside it (week 7 at dt 0.033: stopped by an estimate 0.0469 m away, the TRUE
    position 0.0523 m away)."""
    assert main(_args("week3", tmp_path, solutions=True, dt=0.01)) == 0
    assert "reached: the TRUE position came within 0.0498 m of it (d_stop = 0.05)" in capsys.readouterr().out
    assert main(_args("week7", tmp_path / "7", solutions=True, seconds=30.0)) == 0
    out = capsys.readouterr().out
    assert ("Goal (1.1, 1.1) not reached: the TRUE position came within 0.0523 m of it (d_stop = 0.05); the "
            "robot stopped at t = 27.39 s, 0.0523 m from it (its estimate 0.0469 m from it") in out


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


def test_the_week5_readme_switch_counts_are_the_runs(tmp_path, capsys):
    """Issue 21: the README promised 4 and about 20 switches where the runs (and the report) made 2 and 17.
    The counts it gives are those of the course's switching, as the summary prints them."""
    import re

    from simiam.control.local_brain import LocalBrain
    from simiam.course.loader import load_submission
    from simiam.course.weeks import get_week
    from simiam.simulator import Simulator
    from simiam.world import load_world

    readme = (ROOT / "assignments" / "week5" / "README.md").read_text(encoding="utf-8")
    said = re.search(r"reaches \(1, 1\) with (\d+) switches and\s+\(-1, 1\) with (\d+)", readme)
    assert said, "the README gives the switching runs' switch counts"
    week = get_week(5)
    sub = load_submission(ROOT / "solutions" / "week5", week)
    made = []
    for goal in ((1.0, 1.0), (-1.0, 1.0)):
        brain = LocalBrain(sub, week, week.settings.with_changes(goal=goal, is_blending=False).as_dict())
        Simulator(load_world(week.world), brain, week.spec, dt=week.dt).run(week.seconds)
        made.append(brain.supervisor.switches_seen)
    assert made == [int(said.group(1)), int(said.group(2))]
    assert main(_args("week7", tmp_path, solutions=True, dt=0.05)) == 0
    assert "Switches: 18 (0.3 per second)." in capsys.readouterr().out     # the week-7 README's 18
