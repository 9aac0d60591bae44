"""One week of the course, declared in one place: `Week`, and the supervisor settings a run starts from.

Each week is a file `simiam/course/weeks/weekN.py` holding `WEEK = Week(...)`; everything that differs
between weeks (the robot, the world, the student's files, the blocks new that week, the settings of a run,
its length, the checks, the debug signals) is read from there, so adding a week is adding a file (see
docs/design.md, "Adding a week"). This module imports nothing of the grader: the checks are named by their
module path, as a string.
"""

from __future__ import annotations

import dataclasses
import re
import sys
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from simiam.course.placeholders import Placeholder
from simiam.laps import Gate
from simiam.robot.quickbot import RobotSpec
from simiam.signals import declared

if TYPE_CHECKING:
    from types import FrameType

# The settings a supervisor understands by name (Supervisor attributes); others go in `extra`.
NAMED_SETTINGS = ("v", "goal", "d_stop", "theta_d", "state")
# The other settings a run may give (`extra`, a check's run settings; LocalBrain applies them all): the
# supervisor attributes of later weeks (week 5's thresholds and its mode, week 6's wall), where the estimate
# starts (x, y, theta), and controller gains ({"gains": {"go_to_goal": {"Kp": 4}}}). A name not here (or
# not a state, below) is a misspelling, refused with the closest names rather than set and never read.
EXTRA_SETTINGS = ("d_at_obs", "d_unsafe", "is_blending", "d_fw", "fw_direction", "estimate", "gains")
# The course's states (the controllers the solutions add): a setting named after one gives its gains.
STATES = ("stop", "go_to_angle", "go_to_goal", "avoid_obstacles", "ao_and_gtg", "follow_wall")
# The lines `simiam run` can print after a run (simiam/run.py `summary`): the distance driven, the heading
# error to theta_d, the goal reached or not (a run without a goal prints the distance instead), the
# switches (as grade counts them: Supervisor.switches_seen).
SUMMARY_LINES = ("path", "heading", "goal", "switches")


def unknown_setting(name: object, known: Iterable[str], where: str, kind: str = "setting") -> ValueError:
    """The error for a setting nobody reads: `where` it was given, the name, the known name it most
    likely meant, and every known name, closest first. `kind` names what it is ("setting", "gain")."""
    from simiam.names import unknown_name  # only for a wrong name: the worker imports this module at start

    return ValueError(f"{where}: {unknown_name(kind, name, known)}")


def check_setting_names(settings: Iterable[object], known: Sequence[str], where: str) -> None:
    """Refuse the first name in `settings` that is not in `known` (see `unknown_setting`)."""
    for name in settings:
        if not isinstance(name, str) or name not in known:
            raise unknown_setting(name, known, where)


def _given_at() -> str:
    """'.../weeks/week6.py, line 70' for the code that built a SupervisorSettings (a week file, a check's
    with_changes): the first frame on the stack outside this module, dataclasses and generated code."""
    frame: FrameType | None = sys._getframe(1)
    while frame is not None:
        file = frame.f_code.co_filename
        if file not in (__file__, dataclasses.__file__) and not file.startswith("<"):
            return f"{file}, line {frame.f_lineno}"
        frame = frame.f_back
    return "SupervisorSettings"


@dataclass(frozen=True)
class SupervisorSettings:
    """What a run sets on the student's QBSupervisor before the first step (None: leave the student's value).

    `v` forward speed (m/s), `goal` (x_g, y_g) in metres, `d_stop` arrival radius (m), `theta_d` the
    heading of week 2 (rad), `state` the first controller's name. `extra` is open for later weeks'
    settings (e.g. `{"d_at_obs": 0.15, "d_fw": 0.1}`) and for controller gains
    (`{"go_to_goal": {"Kp": 4}}`), passed on by name as LocalBrain understands them. A name in `extra`
    that is none of EXTRA_SETTINGS and STATES is refused (a ValueError naming the file and line that gave
    it and the known names, closest first): a misspelt setting would be set and never read.
    """

    v: float | None = None
    goal: tuple[float, float] | None = None
    d_stop: float | None = None
    theta_d: float | None = None
    state: str | None = None
    extra: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        clash = sorted(set(self.extra) & set(NAMED_SETTINGS))
        if clash:
            raise ValueError(f"SupervisorSettings: {', '.join(clash)} are fields, not extra settings")
        known = EXTRA_SETTINGS + STATES
        if any(not isinstance(name, str) or name not in known for name in self.extra):  # only then the stack
            check_setting_names(self.extra, known, f"{_given_at()}: SupervisorSettings extra")

    def as_dict(self) -> dict[str, Any]:
        """The settings LocalBrain / RemoteBrain take: the fields that are set, then `extra`."""
        named = {name: getattr(self, name) for name in NAMED_SETTINGS if getattr(self, name) is not None}
        return {**named, **dict(self.extra)}

    def with_changes(self, **changes: Any) -> SupervisorSettings:
        """These settings with some changed (named ones as fields, any other name into `extra`)."""
        named = {k: v for k, v in changes.items() if k in NAMED_SETTINGS}
        extra = {k: v for k, v in changes.items() if k not in NAMED_SETTINGS}
        return replace(self, **named, extra={**dict(self.extra), **extra})


@dataclass(frozen=True)
class Week:
    """Everything one week of the course declares. Instructors: one `WEEK = Week(...)` per week file.

    - `number`, `title`: week N and what it is about; `name` ("weekN") is the folder name under
      assignments/ and solutions/ and the world/command-line spelling.
    - `spec`: the QuickBot of this week (dimensions, wheel limits, IR divider; `brain_first` for week 1).
    - `world`: the packaged world (simiam/world/worlds/<world>.xml) that `simiam run` and the scenarios use.
    - `student_files`: the files of the student's folder, in import order; `required_names`: per file, the
      names it must define (dotted for methods), which the loader checks.
    - `blocks`: the code blocks NEW this week (each a Placeholder: file, function, hint, placeholder code);
      earlier weeks' blocks ship filled in. Their `week` is filled in from `number`.
    - `settings`: the supervisor settings of a run (`simiam run` and the scenario checks' default);
      `seconds`, `dt`, `start`: its length, time step and start pose, one value for `simiam run` and `grade`.
    - `checks`: the module of this week's checks, as a dotted name (e.g. "grader.checks.week3"); it
      defines CHECKS (and may declare PLOTS for the report).
    - `debug_signals`: the names of the debug values the week's trace carries (u_ao, theta_g, ...), each
      declared in simiam/signals.py (its kind and where the brain reads it).
    - `summary`: the lines `simiam run` prints after the run, by name ("heading", "goal", "path", ...).
    - `lap_gate`: for a week whose runs drive laps around an obstacle, the gate a lap crosses
      (simiam.laps.Gate, in the running direction of the week's own run); `simiam run` then prints the
      laps, and the week's checks count them through it. None: no laps.
    - `hidden_variants`: in a few words, what the week's hidden checks vary ("other goals", "either side,
      other start headings and distances d_fw"): `grade`'s terminal output and report say it where
      hidden checks are counted ("2 hidden checks (other goals, drawn per seed) run at official grading").
      Empty for a week without hidden checks.
    """

    number: int
    title: str
    spec: RobotSpec
    world: str
    student_files: tuple[str, ...]
    required_names: Mapping[str, tuple[str, ...]]
    checks: str
    blocks: tuple[Placeholder, ...] = ()
    settings: SupervisorSettings = field(default_factory=SupervisorSettings)
    seconds: float = 10.0
    dt: float = 0.033
    start: tuple[float, float, float] = (0.0, 0.0, 0.0)
    debug_signals: tuple[str, ...] = ()
    summary: tuple[str, ...] = ("path",)
    lap_gate: Gate | None = None
    hidden_variants: str = ""

    def __post_init__(self) -> None:
        where = f"week {self.number}"
        if not isinstance(self.number, int) or self.number < 1:
            raise ValueError(f"Week: number must be a whole number from 1, got {self.number!r}")
        if self.spec.week != self.number:
            raise ValueError(f"{where}: its RobotSpec says week {self.spec.week}")
        if not re.fullmatch(r"[A-Za-z_][\w.]*", self.checks):
            raise ValueError(f"{where}: checks must be a module name like 'grader.checks.week{self.number}'")
        odd = [name for name in self.debug_signals if not name.isidentifier()]
        if odd or len(set(self.debug_signals)) != len(self.debug_signals):
            raise ValueError(f"{where}: debug signals must be distinct identifiers: {self.debug_signals}")
        lines = sorted(set(self.summary) - set(SUMMARY_LINES))
        if lines:
            raise ValueError(f"{where}: unknown summary lines {lines} (known: {', '.join(SUMMARY_LINES)})")
        if self.lap_gate is not None and not isinstance(self.lap_gate, Gate):
            raise ValueError(f"{where}: lap_gate must be a simiam.laps.Gate or None, got {self.lap_gate!r}")
        words = self.hidden_variants
        if not isinstance(words, str) or words != " ".join(words.split()) or words.endswith((".", ",")):
            raise ValueError(f"{where}: hidden_variants must be a few words on one line, without a final "
                             f"stop (they go inside brackets), got {words!r}")
        unknown = sorted(set(self.required_names) - set(self.student_files))
        if unknown:
            raise ValueError(f"{where}: required_names of files that are not student files: {unknown}")
        blocks = []
        for block in self.blocks:
            if block.week not in (0, self.number):
                raise ValueError(f"{where}: block {block.file} {block.scope} says week {block.week}")
            if block.file not in self.student_files:
                raise ValueError(f"{where}: block in {block.file}, which is not a student file")
            blocks.append(replace(block, week=self.number))
        object.__setattr__(self, "blocks", tuple(blocks))
        if len({b.key for b in self.blocks}) != len(self.blocks):
            raise ValueError(f"{where}: a block is declared twice")
        try:  # a misspelt debug signal is an error here, not a column that silently stays empty
            declared(self.debug_signals)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None

    @property
    def name(self) -> str:
        """"week1", "week2", ...: the folder name under assignments/ and solutions/."""
        return f"week{self.number}"

    @property
    def files_to_write(self) -> frozenset[str]:
        """The files with a block new this week (the others ship complete and may be missing)."""
        return frozenset(b.file for b in self.blocks)
