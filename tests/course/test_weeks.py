"""The declared weeks: the registry finds weekN.py files by name, a Week refuses an inconsistent declaration,
and a week added as one file is a week of the course."""

from __future__ import annotations

import dataclasses
import math
import sys
from pathlib import Path

import pytest

import simiam.course.weeks as weeks
from simiam.course.placeholders import Placeholder
from simiam.course.week import SupervisorSettings, Week
from simiam.course.weeks import all_blocks, all_weeks, get_week, previous_week, week_numbers
from simiam.robot.quickbot import MAX_VEL_80RPM, RobotSpec


def test_the_four_weeks_are_found_in_order() -> None:
    assert week_numbers()[:4] == (1, 2, 3, 4)
    assert [w.name for w in all_weeks()][:4] == ["week1", "week2", "week3", "week4"]
    assert all(w.checks == f"grader.checks.{w.name}" for w in all_weeks())


@pytest.mark.parametrize("given", [3, "3", "week3", " Week3 ", "WEEK 3"])
def test_a_week_is_named_as_a_number_or_weekN(given) -> None:
    assert get_week(given).number == 3


@pytest.mark.parametrize("given", [0, 99, "week", "three", "week-1", "3.0", True, ""])
def test_an_unknown_week_names_the_weeks_there_are(given) -> None:
    with pytest.raises(ValueError, match=r"no such week: .*week1, week2, week3, week4"):
        get_week(given)


def test_last_week_is_the_declared_week_before() -> None:
    assert [previous_week(n) for n in (2, 3, 4)] == [1, 2, 3]
    with pytest.raises(ValueError, match="first week"):
        previous_week(1)


def test_each_block_belongs_to_the_week_that_declares_it() -> None:
    for week in all_weeks():
        assert all(b.week == week.number and b.file in week.student_files for b in week.blocks)
    assert not get_week(1).blocks  # week 1 only runs the simulator
    assert get_week(2).files_to_write == {"differential_drive.py", "qb_supervisor.py", "quickbot.py"}
    assert len(all_blocks()) == sum(len(w.blocks) for w in all_weeks())


def test_the_declared_values_of_weeks_1_to_4() -> None:
    """The values the course ran with before the weeks were declared objects (the fidelity tests hold the
    physics; these are what grade and simiam run share)."""
    assert [get_week(n).seconds for n in (1, 2, 3, 4)] == [3.0, 8.0, 30.0, 60.0]
    assert [get_week(n).spec.brain_first for n in (1, 2, 3, 4)] == [True, False, False, False]
    assert [get_week(n).spec.ir_mode for n in (1, 2, 3, 4)] == ["week2", "week2", "week3", "week3"]
    assert get_week(4).spec.min_vel > 0 == get_week(3).spec.min_vel
    assert get_week(2).settings.as_dict() == {"theta_d": math.pi / 4, "v": 0.1}
    assert get_week(3).settings.as_dict() == {"v": 0.2, "goal": (-1.0, 1.0), "d_stop": 0.05}
    assert get_week(4).settings.as_dict() == {"v": 0.15, "state": "avoid_obstacles"}


def test_settings_keep_named_and_open_ones_apart() -> None:
    s = SupervisorSettings(v=0.1, extra={"d_fw": 0.1})
    assert s.as_dict() == {"v": 0.1, "d_fw": 0.1}
    assert s.with_changes(goal=(1.0, 0.0), d_at_obs=0.2).as_dict() == {
        "v": 0.1, "goal": (1.0, 0.0), "d_fw": 0.1, "d_at_obs": 0.2}
    with pytest.raises(ValueError, match="v are fields"):
        SupervisorSettings(extra={"v": 0.3})


def _week(**changes) -> Week:
    fields = dict(number=9, title="t", spec=RobotSpec(week=9, max_vel=MAX_VEL_80RPM, min_vel=0.0,
                                                      ir_mode="week3"),
                  world="week4", student_files=("a.py",), required_names={"a.py": ("A",)},
                  checks="grader.checks.week9",
                  blocks=(Placeholder("a.py", "A.f", hint="h", code="x = 0"),))
    return Week(**{**fields, **changes})


@pytest.mark.parametrize("changes,match", [
    ({"number": 0}, "number must be"),
    ({"spec": RobotSpec(week=4, max_vel=1.0, min_vel=0.0, ir_mode="week3")}, "RobotSpec says week 4"),
    ({"checks": "grader/checks/week9.py"}, "checks must be a module name"),
    ({"required_names": {"b.py": ("B",)}}, "not student files"),
    ({"blocks": (Placeholder("b.py", "f", hint="h", code="x = 0"),)}, "not a student file"),
    ({"blocks": (Placeholder("a.py", "f", hint="h", code="x = 0", week=3),)}, "says week 3"),
    ({"blocks": (Placeholder("a.py", "f", hint="h", code=""),) * 2}, "declared twice"),
    ({"summary": ("path", "laps")}, "unknown summary lines"),
    ({"debug_signals": ("u_ao", "u ao")}, "be distinct identifiers"),
    ({"debug_signals": ("v", "v")}, "be distinct identifiers"),
    ({"lap_gate": (0.0, -1.4, 0.2, 1)}, "lap_gate must be a simiam.laps.Gate"),
    ({"hidden_variants": "other goals."}, "without a final stop"),
    ({"hidden_variants": "other goals\nand worlds"}, "on one line"),
    ({"hidden_variants": 3}, "hidden_variants must be"),
])
def test_an_inconsistent_week_is_refused(changes, match) -> None:
    assert _week().blocks[0].week == 9
    with pytest.raises(ValueError, match=match):
        _week(**changes)


LAST = max(week_numbers())  # the course's last real week: the throwaway week 9 copies it
WEEK9 = '''
from simiam.course.weeks.week{base} import WEEK as _LAST
import dataclasses
WEEK = dataclasses.replace(_LAST, number={number}, spec=dataclasses.replace(_LAST.spec, week={number}),
                           blocks=(), checks="grader.checks.week{base}", seconds=1.5)
'''.replace("{base}", str(LAST))


@pytest.fixture
def extra_weeks(tmp_path: Path, monkeypatch):
    """A folder on the weeks package's path: a week file written there is a week of the course."""
    def forget() -> None:
        for name in [n for n in sys.modules if n.startswith("simiam.course.weeks.week9")]:
            del sys.modules[name]
        weeks.refresh()

    monkeypatch.setattr(weeks, "__path__", [*weeks.__path__, str(tmp_path)])
    forget()
    yield tmp_path
    monkeypatch.undo()
    forget()


def test_a_week_is_added_by_adding_its_file(extra_weeks: Path) -> None:
    (extra_weeks / "week9.py").write_text(WEEK9.format(number=9))
    (extra_weeks / "notes.py").write_text("raise AssertionError('not a week file: never imported')\n")
    weeks.refresh()
    assert week_numbers()[-1] == 9
    assert get_week("week9").seconds == 1.5 and get_week(9).spec.week == 9
    assert previous_week(9) == LAST  # last week is the declared one before, numbers may have gaps
    with pytest.raises(ValueError, match="week9"):
        get_week(10)


def test_a_week_file_must_match_its_name_and_declare_WEEK(extra_weeks: Path) -> None:
    (extra_weeks / "week9.py").write_text(WEEK9.format(number=8))
    weeks.refresh()
    with pytest.raises(ValueError, match=r"week9.py: declares week 8, its file name says week 9"):
        week_numbers()
    sys.modules.pop("simiam.course.weeks.week9")
    (extra_weeks / "week9.py").write_text("WEEK = None\n")
    weeks.refresh()
    with pytest.raises(TypeError, match=r"week9.py: a week file must define WEEK = Week"):
        week_numbers()


def test_a_week_is_immutable() -> None:
    with pytest.raises(dataclasses.FrozenInstanceError):
        get_week(3).seconds = 1.0  # type: ignore[misc]


def test_a_declared_week_reaches_the_command_lines(extra_weeks: Path, tmp_path: Path, capsys,
                                                  monkeypatch) -> None:
    """A week declared as one file (week 9: the last week's robot and files, nothing new to write, 1.5 s)
    is a week of every front door, with no other edit: grade, the platform commands, batch, simiam run,
    the stub generator and migrate."""
    import argparse
    import json
    import shutil

    from grader.batch.runner import parse_week
    from grader.cli import _week as grade_week
    from grader.platforms.cli import _week as platform_week
    from simiam.course import migrate, stubs
    from simiam.run import main as simiam_run

    (extra_weeks / "week9.py").write_text(WEEK9.format(number=9))
    weeks.refresh()
    assert grade_week("week9") == platform_week("9") == parse_week("week9") == 9
    with pytest.raises(ValueError, match="week9"):
        grade_week("week10")

    root = Path(__file__).resolve().parents[2]
    solutions = tmp_path / "solutions"
    for n in range(1, LAST + 1):
        shutil.copytree(root / "solutions" / f"week{n}", solutions / f"week{n}")
    with pytest.raises(Exception, match=r"solutions/week9: week 9 declares differential_drive.py"):
        stubs.generate(solutions)
    shutil.copytree(root / "solutions" / f"week{LAST}", solutions / "week9")
    generated = stubs.generate(solutions)
    assert "assignments/week9/avoid_obstacles.py" in generated.files
    assert "    9: {" in generated.files["simiam/course/shipped_blocks.py"]

    out = tmp_path / "run"
    args = argparse.Namespace(week="week9", path=str(solutions / "week9"), solutions=False, seconds=None,
                              dt=None, out=str(out), world=None)
    assert simiam_run(args) == 0
    trace = json.loads((out / "week9.json").read_text())
    assert trace["week"] == 9 and trace["seconds"] == pytest.approx(1.5, abs=0.04)

    capsys.readouterr()
    moved = argparse.Namespace(week="week9", source=str(solutions / f"week{LAST}"),
                               target=str(solutions / "week9"),
                               dry_run=True)
    assert migrate.main(moved) == migrate.EXIT_USAGE  # this checkout's shipped_blocks.py predates week 9
    assert "has no week9 yet (instructors: python -m simiam.course.stubs)" in capsys.readouterr().err
    manifest: dict = {}  # once the generator has run, migrate carries the last week's blocks into week 9
    exec(generated.files["simiam/course/shipped_blocks.py"], manifest)
    monkeypatch.setattr(migrate, "SHIPPED", manifest["SHIPPED"])
    stubs.write(generated, tmp_path)
    moved.target = str(tmp_path / "assignments" / "week9")
    assert migrate.main(moved) == migrate.EXIT_OK
    assert "simiam migrate week9" in capsys.readouterr().out


def test_a_week_with_hidden_checks_says_what_they_vary() -> None:
    """The line counting hidden checks shows the week's own words (Week.hidden_variants): every week
    that has hidden checks declares them; a week without any says nothing."""
    from grader.checks import checks_for_week

    for week in all_weeks():
        hidden = [c.id for c in checks_for_week(week.number) if c.visibility == "hidden"]
        assert bool(week.hidden_variants) == bool(hidden), (week.name, hidden, week.hidden_variants)
    assert weeks.hidden_variants("week5") == "other start poses and goals, blending and switching"
    assert weeks.hidden_variants(99) == weeks.HIDDEN_VARIANTS_UNSAID


def test_a_misspelt_setting_in_a_week_file_is_refused_naming_file_line_and_the_known_ones(
        extra_weeks: Path) -> None:
    """The kept wrong version (tests/data/weeks/week9_misspelt_setting.py): week 6's settings with
    "fw_directon" in `extra`. The week is refused where it is declared, with the name it meant first."""
    wrong = Path(__file__).resolve().parents[1] / "data" / "weeks" / "week9_misspelt_setting.py"
    text = wrong.read_text()
    (extra_weeks / "week9.py").write_text(text)
    line = next(i for i, t in enumerate(text.splitlines(), 1) if "SupervisorSettings(" in t)
    weeks.refresh()
    with pytest.raises(ValueError) as refused:
        week_numbers()
    message = str(refused.value)
    assert f"week9.py, line {line}: SupervisorSettings extra: unknown setting 'fw_directon' (did you mean " \
           "'fw_direction'?); the settings are, closest first: fw_direction, " in message
    assert all(name in message for name in ("d_fw", "is_blending", "estimate", "gains", "go_to_goal"))


def test_every_weeks_settings_and_a_checks_changes_pass_the_names_check() -> None:
    """Valid settings stay valid: every week's own, and the changes its checks make (week 5's mode)."""
    for week in all_weeks():
        assert week.settings.with_changes(goal=(0.5, 0.5), d_stop=0.02).goal == (0.5, 0.5)
    assert get_week(5).settings.with_changes(is_blending=False).as_dict()["is_blending"] is False
    assert SupervisorSettings(extra={"d_fw": 0.1, "go_to_goal": {"Kp": 4}, "estimate": [0, 0, 1]}).extra
    misspelt = (r"test_weeks.py, line \d+: SupervisorSettings extra: unknown setting 'is_blendng' \(did you "
                r"mean 'is_blending'\?\)")
    with pytest.raises(ValueError, match=misspelt):
        get_week(5).settings.with_changes(is_blendng=False)
    with pytest.raises(ValueError, match="a setting's name is a string, not int 3"):
        SupervisorSettings(extra={3: 1})


def test_the_declared_states_are_the_solutions_controllers() -> None:
    """STATES (the names a week's `extra` may give gains for) are the controllers the course's
    supervisors add: a new controller in a later week is declared there too."""
    from simiam.control.local_brain import LocalBrain
    from simiam.course.loader import load_submission
    from simiam.course.week import STATES

    root = Path(__file__).resolve().parents[2]
    added = set()
    for week in all_weeks():
        submission = load_submission(root / "solutions" / week.name, week)
        assert submission.ok, submission.errors
        added |= set(LocalBrain(submission, week).supervisor.controllers)
    assert added == set(STATES)
