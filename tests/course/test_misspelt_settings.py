"""A setting the student's QBSupervisor sets under a misspelt name (`self.fw_directon`) is set and never
read, and the run keeps the default: `simiam run` warns, naming the file, the line and the setting it most
likely meant; a name the student's own code reads is theirs, whatever it looks like."""

from __future__ import annotations

import argparse
from pathlib import Path

import mistakes

from simiam.course.misspelt_settings import misspelt_settings
from simiam.run import main

ROOT = Path(__file__).resolve().parents[2]


def test_the_kept_wrong_version_is_warned_about_with_its_line(tmp_path: Path, capsys) -> None:
    folder = mistakes.build("submissions", "week6_misspelt_direction", tmp_path, 6)
    line = next(i for i, t in enumerate((folder / "qb_supervisor.py").read_text().splitlines(), 1)
                if "WRONG" in t)
    args = argparse.Namespace(week="week6", path=str(folder), solutions=False, seconds=1.0, dt=0.05,
                              out=str(tmp_path / "out"), world=None)
    assert main(args) == 0  # a warning: the run goes on
    err = capsys.readouterr().err
    assert (f"warning: qb_supervisor.py, line {line}: self.fw_directon is set but never read; did you mean "
            "self.fw_direction? (the settings the simulator reads, closest first: fw_direction, ") in err


def test_the_solutions_and_stubs_of_every_week_are_not_warned_about() -> None:
    for folder in sorted([*ROOT.glob("solutions/week*"), *ROOT.glob("assignments/week*")]):
        supervisor = folder / "qb_supervisor.py"
        if supervisor.is_file():
            assert misspelt_settings(supervisor.read_text()) == [], folder


def test_only_an_unread_name_close_to_a_setting_is_a_misspelling() -> None:
    source = '''
class QBSupervisor:
    def __init__(self):
        self.goals = [(1, 1), (0, 0)]   # read below: the student's own list
        self.d_Stop = 0.1               # other capitals: d_stop
        self.counter = 0                # nothing like a setting
        self.velocity = 0.2             # not close enough to v to guess
        self.d_fw = 0.18                # a setting
    def execute(self, dt):
        self.goal = self.goals[0]
'''
    (warning,) = misspelt_settings(source, "qb_supervisor.py")
    assert warning.startswith("qb_supervisor.py, line 5: self.d_Stop is set but never read; did you mean "
                              "self.d_stop?")
    assert misspelt_settings("def broken(:\n") == []
