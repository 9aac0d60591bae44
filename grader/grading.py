"""grade_submission: the one grading engine behind `grade weekN`, `grade --batch` and the Dask executor.

    result = grade_submission(week=3, submission=Path("assignments/week3"), seed=2014, hidden=False,
                              out_dir=Path("reports"), sandbox="auto")

It splices the submission's START/END blocks into pristine stubs, starts one sandboxed worker on the
spliced copy, runs the week's checks against it and returns the contract's result JSON (a plain dict).
It never raises for a bad submission: a file that does not load fails the checks that need it, with the
file, line and reason; the status is `invalid` only when nothing at all could be loaded.
"""

from __future__ import annotations

import functools
import json
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from grader.checks import Check, Context, checks_for_week, grader_error, run_check
from grader.earlier import SESSION_KEY
from grader.result import CheckResult, loss_summary, submission_result
from grader.result_size import bound_result
from grader.sandbox.errors import MachineStalled, SandboxError
from grader.sandbox.limits import Limits
from grader.sandbox.output import cut_middle
from grader.sandbox.session import StudentSession
from grader.under_load import BLIND_NOTE, REDOS, UNDER_LOAD, run_again_if_stalled, under_load_record
from simiam import safe_write
from simiam.course.shipped import files_to_write, missing_note, shipped_version

DEFAULT_SEED = 2014
HIDDEN_OUTPUT_CHARS = 1500  # per hidden check: shown in its own Gradescope test (4000 characters in all)
ROOT = Path(__file__).resolve().parents[1]


class CourseFilesMissing(RuntimeError):
    """The grader cannot use its pristine skeletons (missing from a broken installation, or out of date
    with solutions/ in a checkout), so it cannot splice anything. Not a student problem: grading stops."""


@dataclass
class _Job:
    """One grading, as grade_submission was asked for it."""

    week: int
    submission: Path
    seed: int
    hidden: bool
    sandbox: str
    case: dict[str, Any] | None
    limits: Limits | None
    replay_prefix: str | None
    selected: list[Check]
    extra: dict[str, Any]
    traces: dict[str, dict]
    began: float
    start_nudge: tuple[float, float] = (0.0, 0.0)
    official: bool = False
    practice: bool = False
    budget: Any = None  # the grading's TimeBudget: the main session's, shared with any other it opens


def select_checks(week: int, hidden: bool, only: str | None = None) -> tuple[list[Check], list[Check]]:
    """(checks to run, hidden checks left out). `only` picks one check id (the CLI's --check). A practice
    grading asks with `hidden` True: its hidden checks run on the practice set."""
    checks = checks_for_week(week)
    if only is not None:
        picked = [c for c in checks if c.id == only]
        if not picked:
            raise ValueError(
                f"week {week} has no check {only!r}; its checks are: " + ", ".join(c.id for c in checks)
            )
        return picked, []
    run = [c for c in checks if hidden or c.visibility == "visible"]
    return run, [c for c in checks if c not in run]


@functools.lru_cache(maxsize=1)
def _skeletons_out_of_date() -> tuple[str, ...]:
    """In a checkout with solutions/: the packaged skeletons that differ from what the generator makes
    now (an instructor edited solutions/ and did not regenerate). Empty where there are no solutions.
    When the skeletons' stamp matches solutions/ (the usual case) nothing is regenerated: ~1 ms instead
    of ~100 ms, once per grading process."""
    from simiam.course import skeleton_stamp

    if not (ROOT / "solutions").is_dir() or skeleton_stamp.up_to_date(ROOT / "solutions"):
        return ()
    from simiam.course.stubs import SKELETONS, differences, generate

    prefix = str(SKELETONS.relative_to(SKELETONS.parents[2])) + "/week"  # the skeletons, not their stamp
    generated = generate(ROOT / "solutions")
    return tuple(d for d in differences(generated, SKELETONS.parents[2]) if d.startswith(prefix))


def pristine_stubs(week: int, into: Path) -> Path:
    """The week's untouched stubs, written into `into/stubs`: always the skeletons packaged with simiam
    (simiam.course.skeletons), never a folder a student can edit such as assignments/weekN."""
    from simiam.course.skeletons import SkeletonsMissing, write_skeleton

    stale = _skeletons_out_of_date()
    if stale:
        raise CourseFilesMissing(
            "the packaged skeletons are out of date with solutions/ (" + ", ".join(stale[:3])
            + "): run `python -m simiam.course.stubs` to regenerate them, then grade again")
    try:
        return write_skeleton(week, into / "stubs")
    except SkeletonsMissing as exc:
        # Without stubs every file would be "not part of the assignment" and every submission would score
        # 0: refuse loudly instead of grading.
        raise CourseFilesMissing(str(exc)) from None


def _splice(week: int, submission: Path, tmp: Path) -> tuple[Path, dict[str, list[str]], list[str]]:
    """Splice into pristine stubs: (spliced folder, problems by file, notices)."""
    from simiam.course.splice import splice_folder

    spliced = tmp / f"week{week}"
    report = splice_folder(pristine_stubs(week, tmp), submission, spliced)
    problems: dict[str, list[str]] = {}
    notices: list[str] = []
    for name, res in report.files.items():
        if res.missing and name in files_to_write(week):
            problems.setdefault(name, []).append(f"{name} is missing from your submission")
        elif res.missing:
            shipped = shipped_version(week, name, ROOT)
            if shipped is not None:
                (spliced / name).write_text(shipped, encoding="utf-8")
            notices.append(missing_note(week, name, shipped is not None))
        problems.setdefault(name, []).extend(f"{e} (the stub's code was used instead)" for e in res.errors)
        notices.extend(f"{edit} (edits outside the code blocks are not run)" for edit in res.outside_edits)
        if not problems[name]:
            del problems[name]
    notices.extend(f"{name}: not part of the assignment (ignored)" for name in report.extra_files)
    return spliced, problems, notices


def _load_problems(week: int, loaded: dict) -> dict[str, list[str]]:
    """Problems by student file from the worker's load report (untrusted: only strings are kept)."""
    from simiam.course.weeks import get_week

    modules = loaded.get("modules", {})
    errors = []
    for e in loaded.get("errors", []):
        file = e.get("file") if isinstance(e.get("file"), str) else ""
        line = e.get("line") if type(e.get("line")) is int else None
        message = e.get("message") if isinstance(e.get("message"), str) else "could not be loaded"
        errors.append((file, f"{file}:{line}: {message}" if line else f"{file}: {message}".lstrip(": ")))
    problems: dict[str, list[str]] = {}
    for file in get_week(week).student_files:
        own = [text for f, text in errors if f == file]
        if own:
            problems[file] = own
        elif file.removesuffix(".py") not in modules:
            others = "; ".join(text for _, text in errors) or "it did not import"
            problems[file] = [f"{file} could not be imported ({others})"]
    return problems


def grade_submission(
    week: int,
    submission: Path | str,
    seed: int = DEFAULT_SEED,
    hidden: bool = False,
    out_dir: Path | str | None = None,
    sandbox: str = "auto",
    *,
    only: str | None = None,
    case: dict[str, Any] | None = None,
    limits: Limits | None = None,
    replay_prefix: str | None = None,
    traces: dict[str, dict] | None = None,
    start_nudge: tuple[float, float] = (0.0, 0.0),
    official: bool = False,
    practice: bool = False,
) -> dict:
    """Grade one submission folder for course week `week` and return the result JSON (see the module doc).

    `hidden` also runs the hidden checks (official grading). `only`/`case` run one check, or one case of a
    property (the replay line a failing property prints). Scenario traces go into `traces` (by check id)
    when a dict is given, and into the HTML report when `out_dir` is given. `start_nudge` (dx, dy) m moves
    the true start pose of every scenario run (Context.start_nudge; tests only, never a command line).
    `official` says this is a platform's official grading (grader.platforms.official): where that machine
    lacks part of the sandbox, the isolation note says so, not "local check only" (capabilities).
    `practice` runs the hidden checks on the practice set shipped with the package (grader.practice)
    instead of the hidden set: their results go into `result["practice"]`, never into the checks, the
    score or `hidden` (the result says which practice variants ran). Not with `hidden`; ValueError for a
    week without a practice set.
    """
    if practice and hidden:
        raise ValueError("--practice runs the practice variants in place of the hidden ones: not with "
                         "--hidden")
    if practice:  # a week without a practice set would run its hidden checks' own draw under that name
        from grader.practice import missing_practice_set

        missing_practice_set([int(week)])
    week = int(week)
    submission = Path(submission)
    traces = {} if traces is None else traces
    began = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="simiam-grade-") as tmp:
        # the worker starts first: it boots while the checks (and the report's templates) are imported
        started = _start(week, submission, Path(tmp), limits, sandbox, official) \
            if submission.is_dir() else None
        try:
            selected, left_out = select_checks(week, hidden or practice, only)
            if practice:  # its hidden checks run on the practice set: as hidden checks none of them ran
                left_out = [c for c in checks_for_week(week) if c.visibility != "visible"]
            if out_dir is not None and started is not None:
                _import_report()
            extra: dict[str, Any] = {
                "hidden": hidden,
                "hidden_checks_not_run": len(left_out),
                "visible_checks": sum(c.visibility == "visible" for c in selected),
            }
            if practice:  # filled by _set_practice_apart; an invalid submission keeps it empty
                extra["practice"] = _practice_record(week, [])
            if started is None:
                result = _invalid(week, seed, submission, selected, f"no such folder: {submission}", extra)
                return _finish(result, traces, out_dir)
            try:
                job = _Job(week, submission, seed, hidden, sandbox, case, limits, replay_prefix, selected,
                           extra, traces, began, (float(start_nudge[0]), float(start_nudge[1])), official,
                           practice)
                result = _grade(job, started)
            except CourseFilesMissing:
                raise
            except Exception as exc:  # noqa: BLE001 - a grader bug: the student is told so, never a traceback
                message, details = grader_error(exc, whole=True)
                extra["grader_error"] = details["grader_error"]
                result = _invalid(week, seed, submission, selected, message, extra)
        finally:
            if started is not None and started.session is not None:
                started.session.close()
    return _finish(result, traces, out_dir)


@dataclass
class _Started:
    """A spliced submission whose worker is starting, or the error that stopped it (raised by _grade)."""

    spliced: Path | None = None
    problems: dict[str, list[str]] = field(default_factory=dict)
    notices: list[str] = field(default_factory=list)
    session: StudentSession | None = None
    error: Exception | None = None


def _start(week: int, submission: Path, tmp: Path, limits: Limits | None, sandbox: str,
           official: bool = False) -> _Started:
    """Splice the submission and spawn its worker without waiting for it (StudentSession.start)."""
    try:
        spliced, problems, notices = _splice(week, submission, tmp)
        session = StudentSession(week, spliced, limits, sandbox=sandbox, official=official)
    except Exception as exc:  # noqa: BLE001 - raised again by _grade, where grade_submission handles it
        return _Started(error=exc)
    session.start()
    return _Started(spliced, problems, notices, session)


def _open_session(job: _Job, folder: Path, others: list[StudentSession]) -> StudentSession:
    """A worker on another folder for one check (closed with the grading's own), on the grading's one
    time budget (issue 30: a second worker never starts with a fresh one)."""
    other = StudentSession(job.week, folder, job.limits, sandbox=job.sandbox, official=job.official,
                           budget=job.budget)
    others.append(other)
    other.start()
    return other


def _import_report() -> None:
    """Import the HTML report (jinja2) now, while the worker starts, rather than after the checks."""
    try:
        import grader.report.html  # noqa: F401
    except ImportError:  # the report package is optional: write_outputs says so
        pass


def _grade(job: _Job, started: _Started) -> dict:
    """Load and run the checks of one spliced submission (grade_submission's work)."""
    if started.error is not None:
        raise started.error
    assert started.session is not None
    problems, session = started.problems, started.session
    job.extra["notices"] = started.notices
    others: list[StudentSession] = []  # sessions checks opened on other folders (grader.earlier)
    job.budget = session.budget
    try:
        try:
            loaded = _load(session)
        except MachineStalled as exc:
            job.extra["under_load"] = under_load_record(["load"], session.budget.stalls)
            job.extra["time_budget"] = session.budget.to_json()
            message = (f"{UNDER_LOAD}: the grading machine was too busy to load your code ({exc.message}), "
                       f"{REDOS + 1} times; this says nothing about your code")
            return _invalid(job.week, job.seed, job.submission, job.selected, message, job.extra)
        except SandboxError as exc:
            job.extra["isolation"] = session.isolation
            job.extra["isolation_note"] = session.isolation_note
            job.extra["numerics"] = session.numerics
            message = f"your code could not be loaded at all: {exc.message}"
            return _invalid(job.week, job.seed, job.submission, job.selected, message, job.extra)
        for file, texts in _load_problems(job.week, loaded).items():
            problems.setdefault(file, []).extend(texts)
        job.extra["isolation"] = session.isolation
        job.extra["isolation_note"] = session.isolation_note
        job.extra["numerics"] = session.numerics  # which BLAS kernel and SIMD level ran the student's code
        if not loaded.get("modules"):
            message = "none of your files could be loaded: " + "; ".join(
                t for v in problems.values() for t in v
            )
            return _invalid(job.week, job.seed, job.submission, job.selected, message, job.extra)
        prefix = job.replay_prefix
        if prefix is None:
            prefix = f"grade week{job.week} {job.submission}"
        ctx = Context(
            week=job.week,
            seed=job.seed,
            session=session,
            hidden=job.hidden,
            case=job.case,
            traces=job.traces,
            replay_prefix=(prefix + (" --hidden" if job.hidden else "")
                           + (" --practice" if job.practice else "") + f" --seed {job.seed}"),
            submission=str(job.submission),
            spliced=started.spliced,
            open_session=lambda folder: _open_session(job, folder, others),
            start_nudge=job.start_nudge,
            practice=job.practice,
        )
        timing: dict[str, float] = {}
        ran: dict[str, CheckResult] = {}
        spoiled: list[str] = []  # checks the machine kept from a verdict (grader.under_load)
        # Visible checks first: what the code prints until then is the result's student_output. Then each
        # hidden check, its output taken after it into its own result: code that prints (or keeps and
        # prints later) a hidden goal shows it only where that check's result is shown.
        visible = [c for c in job.selected if c.visibility == "visible"]
        for check in visible:
            ran[check.id] = _run_timed(check, ctx, problems, timing, spoiled)
        job.extra["student_output"] = cut_middle(session.take_output(), 4000)
        for check in job.selected:
            if check.id not in ran:
                ran[check.id] = _run_timed(check, ctx, problems, timing, spoiled)
                ran[check.id].printed = cut_middle(session.take_output(), HIDDEN_OUTPUT_CHARS)
        results = [ran[check.id] for check in job.selected]
        if job.practice:
            results = _set_practice_apart(job, results)
        job.extra["problems"] = problems
        job.extra["timing"] = {"total_seconds": round(time.monotonic() - job.began, 3), "checks": timing}
        job.extra["time_budget"] = session.budget.to_json()
        if spoiled:
            job.extra["under_load"] = under_load_record(spoiled, session.budget.stalls)
        if session.budget.blind:
            job.extra["notices"] = [*job.extra.get("notices", []), BLIND_NOTE]
    finally:
        session.close()
        for other in others:
            other.close()
    return submission_result(
        week=job.week,
        seed=job.seed,
        submission=str(job.submission),
        checks=checks_for_week(job.week),
        results=results,
        message=loss_summary(results, problems),
        extra=job.extra,
    )


def _set_practice_apart(job: _Job, results: list[CheckResult]) -> list[CheckResult]:
    """The graded results; the practice ones (hidden checks run on the practice set) go into
    `job.extra["practice"]` with no points, so nothing that sums a score can count them."""
    graded = [r for r in results if r.visibility == "visible"]
    records = []
    for r in results:
        if r.visibility != "visible":
            r.visibility = "practice"
            r.name = r.name.replace("drawn per seed", "of the practice set")  # what ran, not the hidden draw
            record = r.to_json()
            del record["points"], record["max_points"]
            records.append(record)
    job.extra["practice"] = _practice_record(job.week, records)
    return graded


def _practice_record(week: int, records: list[dict]) -> dict[str, Any]:
    """`result["practice"]`: what practice is, which variants ran, the practice checks' records."""
    from grader.practice import PRACTICE_NOTE, load_practice

    data = load_practice(week) or {}
    return {"note": PRACTICE_NOTE, "about": str(data.get("about", "")), "variants": data.get("variants", []),
            "checks": records}


def _load(session: StudentSession) -> dict:
    """session.load(), tried again (REDOS times at most) while the machine stalls the worker's start."""
    for attempt in range(REDOS + 1):
        try:
            return session.load()
        except MachineStalled:
            if attempt == REDOS:
                raise
    raise AssertionError("unreachable")


def _run_timed(check: Check, ctx: Context, problems: dict[str, list[str]],
               timing: dict[str, float], spoiled: list[str]) -> CheckResult:
    """Run one check, again while the machine stalls it (grader.under_load); its time into `timing`."""
    t0 = time.monotonic()
    result, stalls = run_again_if_stalled(lambda: run_check(check, ctx, problems), ctx.session.budget,
                                          ctx.memo, keep=lambda key: key == SESSION_KEY)
    if stalls:
        spoiled.append(check.id)
    timing[check.id] = round(time.monotonic() - t0, 3)
    return result


def _invalid(
    week: int, seed: int, submission: Path, selected: list[Check], message: str, extra: dict[str, Any]
) -> dict:
    if "practice" in extra:  # a practice grading: only the graded checks are listed (and scored 0)
        selected = [c for c in selected if c.visibility == "visible"]
    results = [
        CheckResult(c.id, c.name, c.kind, c.visibility, c.weight, status="error", message=message)
        for c in selected
    ]
    return submission_result(
        week=week,
        seed=seed,
        submission=str(submission),
        checks=checks_for_week(week),
        results=results,
        status="invalid",
        message=message,
        extra=extra,
    )


def _finish(result: dict, traces: dict[str, dict], out_dir: Path | str | None) -> dict:
    result = bound_result(result)      # whatever the worker sent, one result stays under 2 MB
    if out_dir is not None:
        write_outputs(result, traces, Path(out_dir))
    return result


def write_outputs(result: dict, traces: dict[str, dict], out_dir: Path) -> tuple[Path, Path | None]:
    """Write weekN.json and (when the report package is present) weekN.html into out_dir, never through a
    link (simiam.safe_write: `grade` runs in a student's folder, whose reports/ anyone may have prepared);
    a link there raises LinkRefused, an OSError."""
    week = result["week"]
    json_path = safe_write.write_text(out_dir / f"week{week}.json", json.dumps(result, indent=1))
    try:
        from grader.report.html import write_report
    except ImportError:
        return json_path, None
    return json_path, write_report(result, traces, out_dir / f"week{week}.html")
