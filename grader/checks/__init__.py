"""The check registry: what a check is, what it gets when it runs, and the checks of each week.

A check has a stable id `weekN.<part>.<name>`, a weight (its max points), a kind (property, scenario,
static) and a visibility (visible: runs everywhere; hidden: only with `--hidden`, i.e. in official
grading). Its `run(ctx)` returns an `Outcome` (a fraction of the points, a message, details); anything the
student's code does wrong on the way is raised as a grader.sandbox error and turned into a clear message by
`run_check`.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

from grader.result import CheckResult
from grader.sandbox.errors import SandboxError, StudentError, StudentTimeout, WorkerDied
from simiam.course.week import Week
from simiam.course.weeks import get_week


class Mismatch(Exception):
    """A student answer that is wrong, with the plain-words reason ("with v = 0.1 ... expected ...")."""


@dataclass
class Outcome:
    """What a check found: the fraction of its points earned (0..1), why, and details for the report."""

    fraction: float
    message: str = ""
    details: dict[str, Any] = field(default_factory=dict)
    status: str | None = None  # default: passed when fraction == 1, else failed


@dataclass
class Context:
    """What a running check may use. `session.call` reaches the student's worker; nothing else does."""

    week: int
    seed: int
    session: Any
    hidden: bool = False
    case: dict[str, Any] | None = None  # replay one case of a property (`grade --check ID --case ...`)
    traces: dict[str, dict] = field(default_factory=dict)  # scenario traces by check id (Seam 2)
    replay_prefix: str = ""  # e.g. "grade week2 path/to/folder"
    call_seconds: float = 2.0
    memo: dict[Any, Any] = field(default_factory=dict)  # runs shared between checks of one grading
    submission: str = ""  # the folder as the student named it (for the replay snippet)
    last_probe: tuple[str, dict[str, Any]] | None = None  # the last probe sent: what a replay repeats
    spliced: Any = None  # the spliced submission folder the session runs (a Path), when the engine has one
    open_session: Callable[[Any], Any] | None = None  # another session on a folder; the engine closes it
    serving: Any = None  # while grader.batched_cases runs a case: its answers (probes are sent in batches)
    # Moves the TRUE start pose of every scenario run by (dx, dy) m, never the estimate: the proof that no
    # verdict hangs on the last bit (tests/grader/test_verdict_margins.py). Only the grading API sets it
    # (grade_submission's start_nudge); no command line, setting or submission reaches it.
    start_nudge: tuple[float, float] = (0.0, 0.0)
    # `grade --practice`: the hidden checks run every variant of the practice set shipped with the package
    # (grader.practice) instead of the seed's draw from the hidden set; their results are never scored
    practice: bool = False

    @property
    def config(self) -> Week:
        """The week's declaration (robot, world, settings, run length)."""
        return get_week(self.week)

    @property
    def spec(self):
        return self.config.spec

    def probe(self, name: str, **args: Any) -> Any:
        """Run probe `name` in the student's worker; the untrusted JSON answer."""
        full = {"week": self.week, **args}
        self.last_probe = (name, full)
        if self.serving is not None:  # a property's cases run batched: the answer comes from the batch
            return self.serving.answer(name, full)
        return self.session.call("probe", name=name, args=full, timeout=self.call_seconds)

    def probe_each(self, name: str, many: Sequence[dict[str, Any]]) -> Iterator[Any]:
        """Probe `name` once with each of `many` (its keyword arguments), all in one request: the answers in
        order, each as `probe` gives it. When an answer is yielded, `last_probe` is its probe, and the
        SandboxError `probe` would have raised for a probe is raised in its place, so a loop over the
        answers fails, and a replay repeats, exactly as the loop with one `probe` a step. The per-probe
        time limit is kept (StudentSession.probe_many). Only for probes that do not depend on each other:
        the probes after the one that fails have run too (each builds the student's objects afresh, so
        only module-level state in student code could tell)."""
        fulls = [{"week": self.week, **args} for args in many]
        if self.serving is not None or len(fulls) < 2:  # inside a batched property case: its own batches
            for args in many:
                yield self.probe(name, **args)
            return
        answers = self.session.probe_many([{"name": name, "args": full} for full in fulls],
                                          timeout=self.call_seconds)
        for k, full in enumerate(fulls):
            self.last_probe = (name, full)
            if k >= len(answers):  # probe_many stops early only after a timeout or a dead worker
                raise RuntimeError(f"probe_many answered {len(answers)} of {len(fulls)} probes")
            if isinstance(answers[k], SandboxError):
                raise answers[k]
            yield answers[k]


# What the report can draw for a scenario run (grader/report/svg.py): the path in the world, the heading
# against the goal direction (settle band), the heading against a fixed theta_d; which controller ran when
# (grader/report/signal_plots.py); and "signals:NAME,NAME" for declared debug signals over time.
PLOTS = ("trajectory", "heading", "angle", "states")
SIGNAL_PLOT = "signals:"


@dataclass(frozen=True)
class Check:
    """One check of one week. `needs`: the student files it runs (a file that did not load fails it).
    `plots`: what the report draws for each run of a scenario check (names from PLOTS); the result
    carries it to the report, which imports no check."""

    id: str
    name: str
    kind: str
    weight: float
    run: Callable[[Context], Outcome]
    needs: tuple[str, ...] = ()
    visibility: str = "visible"
    plots: tuple[str, ...] = ("trajectory",)

    def __post_init__(self) -> None:
        unknown = sorted(p for p in self.plots if p not in PLOTS and not p.startswith(SIGNAL_PLOT))
        if unknown:
            raise ValueError(f"check {self.id}: unknown plots {unknown} (known: {', '.join(PLOTS)})")

    @property
    def part(self) -> str:
        return self.id.split(".")[1]


def checks_for_week(week: int) -> list[Check]:
    """Every check of `week` (visible and hidden), in report order: the CHECKS of the module the week
    declares (`Week.checks`)."""
    module = importlib.import_module(get_week(week).checks)
    return list(module.CHECKS)


def sandbox_message(exc: SandboxError) -> tuple[str, str]:
    """(status, message) for a failure of the student's worker during a check."""
    if isinstance(exc, StudentTimeout):
        return "timeout", f"your code did not answer in time: {exc.message}"
    if isinstance(exc, StudentError):
        return "error", f"your code raised an error: {exc}"
    if isinstance(exc, WorkerDied):
        return "error", f"your code stopped the grading worker: {exc.message}"
    return "error", str(exc)


GRADER_ERROR = "grader error, not your fault"


def grader_error(exc: BaseException, whole: bool = False) -> tuple[str, dict[str, Any]]:
    """(message, details) for a bug in the grader itself: the student is told it is not their fault and
    to report it; the details keep where in the grader it happened, for whoever fixes it. `whole`: the
    bug stopped the whole grading, not one check."""
    import traceback
    from pathlib import Path

    package = Path(__file__).resolve().parents[1]
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if Path(f.filename).is_relative_to(package)]
    where = f"{Path(frames[-1].filename).relative_to(package)}:{frames[-1].lineno}" if frames else "?"
    what, rest = ("your submission could not be graded", "") if whole else (
        "this check could not be finished", "; your other checks are not affected")
    message = (
        f"{GRADER_ERROR}: {what} because of a bug in the grader ({type(exc).__name__} in grader/{where}). "
        f"Please report it to the course staff with this message{rest}."
    )
    return message, {"grader_error": {"type": type(exc).__name__, "message": str(exc)[:300], "where": where}}


def run_check(check: Check, ctx: Context, load_errors: dict[str, list[str]]) -> CheckResult:
    """Run one check and turn whatever happens into a CheckResult (never raises for student problems)."""
    result = CheckResult(
        id=check.id, name=check.name, kind=check.kind, visibility=check.visibility, max_points=check.weight,
        plots=check.plots if check.kind == "scenario" else (),
    )
    broken = [msg for file in check.needs for msg in load_errors.get(file, [])]
    if broken:
        result.status = "error"
        result.message = "this check needs code that did not load: " + "; ".join(broken)
        return result
    try:
        outcome = check.run(ctx)
    except SandboxError as exc:
        result.status, result.message = sandbox_message(exc)
        if result.status == "timeout":  # the command that runs this check alone, to see where it hangs
            result.details = {"replay": f"{ctx.replay_prefix} --check {check.id}".strip()}
        return result
    except Mismatch as exc:
        result.message = str(exc)
        return result
    except Exception as exc:  # noqa: BLE001 - a grader bug must not stop the other checks (fail closed)
        result.status = "error"
        result.message, result.details = grader_error(exc)
        return result
    fraction = min(max(float(outcome.fraction), 0.0), 1.0)
    result.points = fraction * check.weight
    result.status = outcome.status or ("passed" if fraction >= 1.0 else "failed")
    result.message = outcome.message
    result.details = outcome.details
    if result.status == "timeout" and "replay" not in result.details:
        result.details = {**result.details, "replay": f"{ctx.replay_prefix} --check {check.id}".strip()}
    return result
