"""`simiam run --start X,Y,THETA` (issue 31): the week-6 README asks students to start turned around, which
before needed a packaged world XML edited by hand. And what the week 5-7 READMEs say of earlier weeks' code
is what a local `grade` does (grader.earlier.OWN_CODE_NOTE)."""

from __future__ import annotations

import argparse
import json
import math
import re
import shlex
import shutil
from pathlib import Path

import pytest

from grader.earlier import OWN_CODE_NOTE
from simiam.cli import _parser
from simiam.run import main, parse_start

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize(("text", "pose"), [
    ("0,0,pi", (0.0, 0.0, math.pi)), ("-0.5, 0.2, -pi/2", (-0.5, 0.2, -math.pi / 2)),
    ("1,1,0.5*pi", (1.0, 1.0, math.pi / 2)), ("0,0,3pi/4", (0.0, 0.0, 3 * math.pi / 4)),
    ("0.1,-0.1,1.5708", (0.1, -0.1, 1.5708)),
])
def test_a_start_is_read_as_people_write_it(text: str, pose: tuple) -> None:
    assert parse_start(text) == pytest.approx(pose, abs=1e-15)


@pytest.mark.parametrize(("text", "says"), [
    ("0,0", "three numbers"), ("0,0,0,0", "three numbers"), ("a,0,0", "X must be a number"),
    ("0,nan,0", "Y must be a finite number"), ("1e9,0,0", "outside any course world"),
    ("0,0,pi/0", "finite angle"), ("0,0,1e300", "between -pi and pi"), ("0,0,tau", "THETA must be a number"),
])
def test_a_bad_start_gets_a_clear_error(text: str, says: str) -> None:
    with pytest.raises(ValueError, match=re.escape(says)):
        parse_start(text)


def _args(argv: list[str], out: Path) -> argparse.Namespace:
    args = _parser().parse_args(argv)
    args.out = str(out)
    return args


def test_the_week6_readme_turns_the_robot_around_with_a_command_that_runs(tmp_path, capsys) -> None:
    readme = (ROOT / "assignments/week6/README.md").read_text()
    turn = readme[readme.index("turn the robot around"):]
    command = re.search(r"^(simiam run week6 --start [^\s#]+)", turn, re.M)
    assert command, "the week-6 README's turn-around paragraph shows no `simiam run week6 --start ...`"
    folder = tmp_path / "week6"
    shutil.copytree(ROOT / "solutions/week6", folder, ignore=shutil.ignore_patterns("__pycache__"))
    supervisor = folder / "qb_supervisor.py"
    supervisor.write_text(supervisor.read_text().replace('fw_direction = "left"', 'fw_direction = "right"'))
    argv = shlex.split(command.group(1))[1:]
    argv[2:2] = [str(folder)]  # the folder the README's command finds by itself in a student's week6/
    argv += ["--seconds", "2"]
    assert main(_args(argv, tmp_path / "runs")) == 0, capsys.readouterr().err
    steps = json.loads((tmp_path / "runs/week6.json").read_text())["steps"]
    assert (steps["x"][0], steps["y"][0], steps["theta"][0]) == (0.0, 0.0, math.pi)
    assert steps["theta_est"][0] == math.pi  # odometry starts where the robot does


def test_a_bad_start_stops_the_run_before_it_starts(tmp_path, capsys) -> None:
    args = _args(["run", "week6", "--solutions", "--start", "0,0"], tmp_path / "runs")
    assert main(args) == 2
    assert "--start '0,0': give three numbers X,Y,THETA" in capsys.readouterr().err
    assert not (tmp_path / "runs").exists()


@pytest.mark.parametrize("week", [5, 6, 7])
def test_the_readme_says_what_a_local_grade_does_with_earlier_weeks_code(week: int) -> None:
    """grade in a student's installation runs their own earlier code and says so (OWN_CODE_NOTE); a
    README saying only "the runs use the course's versions" is not true there."""
    assert "your own code for earlier weeks" in OWN_CODE_NOTE and "official grading" in OWN_CODE_NOTE
    text = " ".join((ROOT / f"assignments/week{week}/README.md").read_text().split())
    at = text.index("the course's versions of the earlier weeks' code")
    paragraph = text[max(0, at - 200):at + 400]
    assert "official grading" in paragraph and "your own installation has no answers" in paragraph, paragraph
    assert "says so" in paragraph, paragraph
