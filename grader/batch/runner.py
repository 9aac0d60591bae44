"""``grade weekN --batch DIR``: grade a whole class, resumably, on this machine or a Dask cluster.

The run, in order:

1. list the students in DIR: one sub-folder or ``.zip`` each, named by student id, or a course platform's
   download as it comes (grader/batch/intake.py), with the roster and late policy laid over them;
2. for each student, lazily as grading slots free up: read the files safely, hash them, and skip the
   student if their stored result carries the same cache key (submission, grader, seed, hidden set;
   ``--only`` regrades the students it names, and only them); a refused submission gets ``invalid`` at
   once without using a grading process;
3. grade the rest in parallel, each in its own killable grading process under a wall budget
   (``timeout`` and ``crashed`` when that process hangs or dies);
4. write each student's ``<id>.html`` then ``<id>.json`` atomically as soon as they finish (the result
   it replaces kept under ``history/``, grader.batch.history);
5. rebuild ``gradebook.csv``, the platform exports (grader.batch.exports), ``summary.html`` and
   ``batch.json`` from the per-student JSON files, also after Ctrl-C, so a rerun of the same command
   simply resumes.

A batch is official grading: the hidden checks run unless ``--visible-only``.

Every student gets the same seed (the contract: ``--seed N`` fixes every random choice), so results are
comparable across the class and do not depend on order or ``--jobs``. Without ``--seed`` the output
folder's own secret seed is used (random on the first run, kept in ``out/.seed``), never the public
default, so hidden goals and worlds cannot be reproduced at home. Timing lives under ``"timing"``
in each result, apart from what is compared.
"""

from __future__ import annotations

import argparse
import copy
import dataclasses
import difflib
import math
import os
import signal
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path
from typing import Any, TextIO

from grader.batch import history
from grader.batch.cache import cache_key, grader_fingerprint, is_fresh
from grader.batch.executors import DaskExecutor, ExecutorError, LocalExecutor
from grader.batch.exports import DEFAULT_CANVAS_TITLE, write_exports
from grader.batch.fallback_page import fallback_page
from grader.batch.identity import Identity
from grader.batch.intake import ClassList, IntakeError, IntakeOptions, read_class
from grader.batch.late_apply import settle_late, with_late_section
from grader.batch.names import shown, student_stem
from grader.batch.pages import REPLAYS, replay_pages, write_assets, write_student_pages
from grader.batch.progress import Progress
from grader.batch.store import (
    OutputBusy,
    entries,
    exclusive,
    folder_seed,
    move,
    read_json,
    write_atomic,
    write_json,
)
from grader.batch.stored import well_formed
from grader.batch.submissions import Student, Submission, pack, read_submission
from grader.batch.summary import write_summary
from grader.hidden.identity import hidden_set_identity
from grader.result_size import bound_html, bound_result
from grader.untrusted import printable
from simiam.course.weeks import get_week, week_numbers

# grade_submission bounds each student check with its own timeouts; this budget only catches a grading
# process that hangs or thrashes as a whole.
DEFAULT_BUDGET_S = 300.0
STATUSES = ("graded", "invalid", "held", "timeout", "crashed")
MAX_PAGE_BYTES = 4 * 1024 * 1024     # a stored page read back to change its late section


class BatchError(Exception):
    """The batch cannot run at all (exit status 2)."""


def under_load(result: dict) -> list[str]:
    """The checks of a stored result the machine kept from a verdict ("load": the whole submission);
    [] for one graded in full. The result is read back from disk: anything malformed counts as none."""
    record = result.get("under_load")
    checks = record.get("checks") if isinstance(record, dict) else None
    if not isinstance(checks, list):
        return []
    return [printable(str(c))[:100] for c in checks[:50]] or ["?"]


def default_jobs() -> int:
    """The number of cores this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


@dataclass
class BatchOptions:
    """Everything a batch run needs; :meth:`from_args` reads the ``grade`` command line."""

    week: int
    batch_dir: Path
    out: Path
    seed: int | None = None          # None: the output folder's secret seed (grader.batch.store.folder_seed)
    jobs: int = field(default_factory=default_jobs)
    hidden: bool = True              # official grading; False only with --visible-only
    force: bool = False
    only: tuple[str, ...] = ()       # --only: regrade these students (even unchanged) and no one else
    canvas_assignment: str = DEFAULT_CANVAS_TITLE
    quiet: bool = False
    executor: str = "local"
    scheduler: str | None = None
    sandbox: str = "auto"
    budget_s: float = DEFAULT_BUDGET_S
    intake: IntakeOptions = field(default_factory=IntakeOptions)   # roster, times, late policy
    similarity: bool = False         # --similarity: similarity.html after grading (grader/similarity)

    @classmethod
    def from_args(cls, args: argparse.Namespace) -> BatchOptions:
        """Options from the ``grade`` parser (grader/cli.py), tolerant of what it leaves at defaults."""
        given = vars(args)
        week = parse_week(given.get("week_number") or given["week"])
        out = given.get("out")
        if not out or out == "reports":      # the single-submission default: keep a batch apart from it
            out = Path("reports") / f"batch-week{week}"
        seed = given.get("seed")
        if seed is not None and not isinstance(seed, int):
            from grader.batch.seed import parse_seed

            try:
                seed = parse_seed(seed)
            except ValueError as exc:
                raise BatchError(str(exc)) from None
        only = tuple(dict.fromkeys(i.strip() for i in (given.get("only") or "").split(",") if i.strip()))
        if given.get("only") is not None and not only:
            raise BatchError("--only needs at least one student id (--only ID[,ID...])")
        # --hidden is accepted for old scripts: a batch runs the hidden checks unless --visible-only
        return cls(week=week, batch_dir=Path(given["batch"]), out=Path(out), seed=seed,
                   jobs=int(given.get("jobs") or default_jobs()), hidden=not given.get("visible_only"),
                   force=bool(given.get("force")), quiet=bool(given.get("quiet")), only=only,
                   canvas_assignment=given.get("canvas_assignment") or DEFAULT_CANVAS_TITLE,
                   executor=given.get("executor") or "local", scheduler=given.get("scheduler"),
                   sandbox=given.get("sandbox") or "auto",
                   budget_s=float(given.get("timeout") or DEFAULT_BUDGET_S),
                   intake=IntakeOptions.from_args(given), similarity=bool(given.get("similarity")))


def parse_week(value: object) -> int:
    """3, "3" or "week3" -> 3 (a declared week; BatchError naming the weeks there are)."""
    try:
        return get_week(str(value)).number
    except ValueError as exc:
        raise BatchError(str(exc)) from None


def main(args: argparse.Namespace) -> int:
    """Entry point behind ``grade weekN --batch DIR``. Exit status: 0 every submission graded (with
    ``--only``: every named one), 1 some invalid, timed out or crashed, 2 the batch could not run, 130
    interrupted (rerun to resume)."""
    def stop(_signum: int, _frame: Any) -> None:
        raise KeyboardInterrupt
    try:
        signal.signal(signal.SIGTERM, stop)     # a kill from a scheduler stops as cleanly as Ctrl-C
    except ValueError:
        pass                                    # not the main thread
    try:
        options = BatchOptions.from_args(args)
        report = run_batch(options)
    except BatchError as exc:
        print(f"grade: {printable(exc)}", file=sys.stderr)
        return 2
    except OSError as exc:          # disk full, read-only --out...: what was written so far stays valid
        print(f"grade: the batch stopped: {printable(exc)}; fix this and rerun the same command to resume",
              file=sys.stderr)
        return 2
    if report["interrupted"]:
        return 130
    if options.only:        # what was asked: every named student graded
        named = [report["per_student"].get(s, {}).get("status") for s in options.only]
        return 0 if all(status == "graded" for status in named) else 1
    return 0 if report["counts"]["graded"] == report["students"] else 1


def make_executor(options: BatchOptions) -> LocalExecutor | DaskExecutor:
    """The executor the options ask for."""
    if options.executor == "local":
        return LocalExecutor(options.jobs, options.budget_s)
    if options.executor == "dask":
        return DaskExecutor(options.scheduler, options.budget_s, jobs=options.jobs)
    raise BatchError(f"unknown executor {options.executor!r}; use 'local' or 'dask'")


def run_batch(options: BatchOptions, grade_fn: Callable[[dict], dict] | str | None = None,
              executor: Any = None, stream: TextIO | None = None) -> dict:
    """Grade the class and return the run record written to ``batch.json``.

    ``grade_fn(task) -> {"result": ..., "html": ...}`` defaults to :func:`grader.batch.task.grade_task`;
    tests inject fakes. Raises BatchError if the batch cannot start.
    """
    if options.week not in week_numbers():
        raise BatchError(f"there is no week {options.week}; the course has weeks "
                         f"{', '.join(map(str, week_numbers()))}")
    out = options.out.resolve()
    if out == options.batch_dir.resolve():
        raise BatchError("--out must not be the class folder itself; choose another folder")
    try:
        klass = read_class(options.batch_dir, options.intake, out)
    except IntakeError as exc:
        raise BatchError(str(exc)) from None
    students = klass.students
    if not students:
        raise BatchError(f"{options.batch_dir} has no student folders or .zip files"
                         if klass.layout == "folder" else f"{options.batch_dir}: no submissions found")
    stems = _stems(students)
    _check_only(options.only, students)
    executor = executor if executor is not None else make_executor(options)
    try:
        with exclusive(out):
            options = dataclasses.replace(options, seed=folder_seed(out, options.seed))
            write_assets(out)
            run = _Run(options, out, klass, stems, stream)
            try:
                executor.run(grade_fn or "grader.batch.task:grade_task", run.plan(), run.finish)
            except KeyboardInterrupt:
                run.interrupted = True
            finally:
                run.progress.close()
            if options.similarity and not run.interrupted:    # before the summary, which links to it
                from grader.similarity.command import after_batch
                try:
                    after_batch(klass, options.week, out, None if options.quiet else run.progress.stream)
                except KeyboardInterrupt:
                    run.interrupted = True
            return run.rebuild(executor.describe())
    except OutputBusy as exc:
        raise BatchError(str(exc)) from None
    except ExecutorError as exc:
        raise BatchError(str(exc)) from None


def _stems(students: list[Student]) -> dict[str, str]:
    """Each student's output file stem; refuses (BatchError) to map two students to one file, also on a
    case-insensitive file system. :func:`student_stem` makes this impossible short of a hash collision;
    the check keeps it so whatever changes there."""
    stems: dict[str, str] = {}
    taken: dict[str, str] = {}
    for student in students:
        stem = student_stem(student.id)
        other = taken.setdefault(stem.casefold(), student.id)
        if other != student.id:
            raise BatchError(f"students {shown(other)!r} and {shown(student.id)!r} would share the output "
                             f"file {stem}; rename one of them")
        stems[student.id] = stem
    return stems


def _check_only(only: tuple[str, ...], students: list[Student]) -> None:
    """BatchError, naming the nearest ids of the class, if ``--only`` names a student the class does not
    have: nothing is graded then (a typo must not silently regrade no one)."""
    known = [s.id for s in students]
    unknown = [i for i in only if i not in set(known)]
    if not unknown:
        return
    lines = []
    for sid in unknown[:20]:
        near = difflib.get_close_matches(sid, known, n=3, cutoff=0.6)
        lines.append(f"{shown(sid)!r}" + (f" (did you mean {', '.join(repr(shown(n)) for n in near)}?)"
                                          if near else ""))
    more = f" and {len(unknown) - 20} more" if len(unknown) > 20 else ""
    raise BatchError(f"--only names {len(unknown)} student(s) the class does not have: "
                     f"{'; '.join(lines)}{more}; nothing was graded")


class _Run:
    """State of one batch run: what is pending, what finished, and the progress line."""

    def __init__(self, options: BatchOptions, out: Path, klass: ClassList, stems: dict[str, str],
                 stream: TextIO | None):
        self.options, self.out, self.students, self.stems = options, out, klass.students, stems
        self.klass = klass
        assert options.seed is not None, "run_batch resolves the seed (folder_seed) before a run starts"
        self.seed: int = options.seed
        self.grader = grader_fingerprint()
        # the hidden set this grading runs (None with --visible-only): its digest is in the cache key, so an
        # edited hidden set regrades everyone; results keep it without the variants (no hidden goal in a
        # file a student may be handed), batch.json with them
        try:
            self.hidden_set = hidden_set_identity(options.week, self.seed) if options.hidden else None
        except (ValueError, KeyError, TypeError) as exc:    # a hand-edited weekN.json that does not parse
            raise BatchError(f"the hidden set of week {options.week} cannot be read ({printable(exc)}); "
                             f"fix instructor_tools/hidden/week{options.week}.json") from None
        self.progress = Progress(len(self.students), stream=stream, quiet=options.quiet)
        for line in [] if options.quiet else klass.messages():
            self.progress.message(line)
        self.pending: dict[str, tuple[Submission, str]] = {}
        self.record: dict[str, dict] = {}
        self.interrupted = False
        self.started = datetime.now(timezone.utc)
        self.clock = time.monotonic()

    def plan(self) -> Iterator[dict]:
        """Tasks for the students that need grading, read one at a time as slots free up."""
        only = set(self.options.only)
        for student in self.longest_first():
            stem = self.stems[student.id]
            if only and student.id not in only:     # --only: the others are left as they are
                stored = read_json(self.out / f"{stem}.json")
                if stored is not None:
                    self.record[student.id] = {"status": stored.get("status"), "cached": True}
                self.progress.done("skipped")
                continue
            submission = read_submission(student, week=self.options.week)
            key = cache_key(self.options.week, self.seed, self.options.hidden, submission.sha256,
                            self.grader, hidden_set=self.hidden_set["digest"] if self.hidden_set else "")
            stored = read_json(self.out / f"{stem}.json")
            # a result the machine spoiled (grader.under_load) is graded again by the next run, never reused
            if (not self.options.force and not only and is_fresh(stored, key)
                    and (self.out / f"{stem}.html").is_file()
                    and not (isinstance(stored, dict) and stored.get("under_load"))):
                assert stored is not None
                if self._restate(student, stem, stored):
                    self.record[student.id] = {"status": stored["status"], "cached": True}
                    self.progress.done("skipped")
                    continue
            self.pending[student.id] = (submission, key)
            display = shown(student.path.name) if student.kind in ("folder", "zip", "link", "clash") \
                else f"{shown(student.path.name)}: {shown(student.id)}"     # one of a platform's download
            task = {"student": student.id, "display": display, "week": self.options.week,
                    "seed": self.seed, "hidden": self.options.hidden, "sandbox": self.options.sandbox,
                    "grader": self.grader, "check_grader": self.options.executor == "dask"}
            if submission.held is not None:
                self.finish(task, {"status": "held", "value": None, "message": submission.held,
                                   "seconds": 0.0})
                continue
            if submission.refused is not None:
                self.finish(task, {"status": "invalid", "value": None, "message": submission.refused,
                                   "seconds": 0.0})
                continue
            task["files"] = pack(submission.files)
            if submission.notices:
                task["notices"] = submission.notices
            yield task

    def _identity(self, student: Student) -> Identity:
        return student.identity or Identity(id=student.id)

    def _restate(self, student: Student, stem: str, stored: dict) -> bool:
        """Bring a reused result up to this run's identity and late policy without grading it again (its
        page's late section too); False when it must be graded again (its numbers cannot be trusted)."""
        identity = self._identity(student)
        # the result as it was, for history/ when the late policy changes its score (a copy only then)
        before = copy.deepcopy(stored) if self.klass.policy is not None or "late" in stored else None
        changed = settle_late(stored, identity, self.klass.policy, self.klass.extensions.get(student.id))
        if changed is None:
            return False
        batch = stored["batch"]
        if not changed and batch.get("identity") == identity.to_json():
            return True
        if changed and before is not None:
            batch["change"] = history.change(before, stored, history.archive(self.out, stem, before))
        if changed:
            page = self.out / f"{stem}.html"
            try:
                with page.open("rb") as stream:
                    text = stream.read(MAX_PAGE_BYTES + 1).decode("utf-8", "replace")
            except OSError:
                return False
            if len(text) > MAX_PAGE_BYTES:
                return False
            write_atomic(page, with_late_section(text, stored.get("late")))
        batch["identity"] = identity.to_json()
        write_json(self.out / f"{stem}.json", stored)
        return True

    def longest_first(self) -> list[Student]:
        """The students in the order to grade them: the class folder's order, except that those whose
        last grading into this folder took far longer than the typical one (a hung or very slow
        submission: over twice the median plus 5 s) go first, longest first, so that they do not run
        alone at the end while the other grading processes have nothing left to do. Results do not
        depend on the order (one seed for all)."""
        last: dict[str, float] = {}
        for student in self.students:
            stored = read_json(self.out / f"{self.stems[student.id]}.json") or {}
            timing = tm if isinstance(tm := stored.get("timing"), dict) else {}
            seconds = timing.get("batch_seconds")
            if isinstance(seconds, (int, float)) and not isinstance(seconds, bool) and math.isfinite(seconds):
                last[student.id] = float(seconds)
        known = sorted(last.values())
        slow = 2 * known[len(known) // 2] + 5.0 if known else math.inf
        outliers = sorted((s for s in self.students if last.get(s.id, 0.0) > slow), key=lambda s: -last[s.id])
        return outliers + [s for s in self.students if s not in outliers]

    def finish(self, task: dict, outcome: dict) -> None:
        """Store one student's outcome: HTML first, then the JSON that marks them done."""
        sid = task["student"]
        submission, key = self.pending.pop(sid)
        result, html = self._settle(task, outcome)
        result["submission"] = task["display"]
        if submission.notices and not result.get("notices"):   # not graded: what the intake noticed
            result["notices"] = list(submission.notices)
        identity = self._identity(submission.student)
        result["grader_version"] = self.grader      # the batch's one version string (grader.batch.task)
        result["batch"] = {"student": sid, "cache_key": key, "submission_sha256": submission.sha256,
                           "grader": self.grader, "root": submission.root, "identity": identity.to_json(),
                           "hidden_set": None if self.hidden_set is None else
                           {k: v for k, v in self.hidden_set.items() if k != "variants"}}
        if result.get("status") == "held":
            result["score"] = None          # not graded, not charged: exports leave the grade blank
        elif settle_late(result, identity, self.klass.policy, self.klass.extensions.get(sid)) is None:
            result.update(status="crashed", score=0.0, message="the grader returned a score out of range")
        if outcome.get("traceback"):
            result["batch"]["traceback"] = outcome["traceback"]
        timing = tm if isinstance(tm := result.get("timing"), dict) else {}
        result["timing"] = {**timing, "batch_seconds": round(float(outcome.get("seconds") or 0.0), 3),
                            "graded_at": datetime.now(timezone.utc).isoformat(timespec="seconds")}
        stem = self.stems[sid]
        earlier = self._earlier(stem)
        kept = history.archive(self.out, stem, earlier) if earlier is not None else None
        asked = "only" if sid in self.options.only else "force" if self.options.force else None
        result["batch"]["change"] = history.change(earlier, result, kept, asked)
        result = bound_result(result)
        # The old JSON goes first (kept in history/ above): until the new one is written this student has
        # no result, so their HTML and JSON never come from two different gradings.
        (self.out / f"{stem}.json").unlink(missing_ok=True)
        html = bound_html(html) if isinstance(html, str) else None
        page = html or fallback_page(shown(sid), result)
        replays = replay_pages(outcome.get("value")) if html else {}
        write_student_pages(self.out, stem, with_late_section(page, result.get("late")), replays)
        write_json(self.out / f"{stem}.json", result)
        status = result["status"]
        self.record[sid] = {"status": status, "cached": False, "seconds": result["timing"]["batch_seconds"],
                            # when, in this run: how long --jobs kept every grading process busy
                            "finished_s": round(time.monotonic() - self.clock, 3)}
        if status != "graded":
            self.progress.message(f"{shown(sid)}: {status}: {str(result.get('message', ''))[:300]}")
        if under_load(result):
            self.progress.message(f"{shown(sid)}: graded under load: regrade "
                                  f"({', '.join(under_load(result)[:6])} got no verdict on this machine)")
        self.progress.done(status)

    def _earlier(self, stem: str) -> dict | None:
        """The student's last stored result: the one in the folder, else the one moved to superseded/."""
        for path in (self.out / f"{stem}.json", self.out / "superseded" / f"{stem}.json"):
            stored = read_json(path)
            if stored is not None:
                return stored
        return None

    def _settle(self, task: dict, outcome: dict) -> tuple[dict, str | None]:
        """The student's result from the grading outcome; anything malformed counts as ``crashed``."""
        if outcome.get("status") == "ok":
            value = outcome.get("value")
            result = value.get("result") if isinstance(value, dict) else None
            if isinstance(value, dict) and isinstance(result, dict) and result.get("status") in STATUSES:
                return dict(result), value.get("html")
            outcome = {"status": "crashed", "message": "the grader returned no usable result"}
        status = outcome.get("status") if outcome.get("status") in STATUSES else "crashed"
        return {"week": task["week"], "score": 0.0, "max_score": None, "status": status,
                "seed": task["seed"], "hidden": task["hidden"], "grader_version": self.grader,
                "submission": task["display"],
                "checks": [], "message": outcome.get("message") or status}, None

    def rebuild(self, executor: dict) -> dict:
        """Class files from the per-student JSONs on disk; returns the ``batch.json`` record."""
        results = {}
        for student in self.students:
            stored = read_json(self.out / f"{self.stems[student.id]}.json")
            if well_formed(stored) and self._current(stored):  # a malformed one waits for its regrade
                results[student.id] = stored
            else:
                self._supersede(self.stems[student.id])
        stems = {sid: self.stems[sid] for sid in results}
        self._prune_gradescope(set(stems.values()))
        not_graded = sorted(shown(s.id) for s in self.students if s.id not in results)
        regrade = sorted(shown(sid) for sid, r in results.items() if under_load(r))
        counts = dict.fromkeys(STATUSES, 0)
        for result in results.values():
            status = result.get("status")
            counts[status if isinstance(status, str) and status in counts else "crashed"] += 1
        if not counts["held"]:
            del counts["held"]          # named only when some student is held
        incomplete = len(self.students) - len(results)
        held = {shown(sid): str(r.get("message") or "")[:300] for sid, r in sorted(results.items())
                if r.get("status") == "held"}
        meta = {"week": self.options.week, "seed": self.seed, "hidden": self.options.hidden,
                "grader": self.grader, "incomplete": incomplete, "not_graded": not_graded,
                "changed": history.changed_rows(results, self.started),
                **self.klass.meta(), "held": sorted(held), "held_reasons": held}
        exported = write_exports(self.out, results, stems, meta, week=self.options.week,
                                 title=self.options.canvas_assignment)
        write_summary(self.out, results, stems, meta)
        report = {"format": "simiam-batch/1", **meta, "hidden_set": self.hidden_set,
                  "only": list(self.options.only), "batch_dir": str(self.options.batch_dir.resolve()),
                  "out": str(self.out), "force": self.options.force, "sandbox": self.options.sandbox,
                  **executor, "started": self.started.isoformat(timespec="seconds"),
                  "finished": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                  "seconds": round(time.monotonic() - self.clock, 3), "interrupted": self.interrupted,
                  "students": len(self.students), "counts": counts, "exports": exported,
                  # students the machine kept from a verdict (grader.under_load): the next run grades them
                  "under_load": regrade,
                  "this_run": {"graded_now": sum(not r["cached"] for r in self.record.values()),
                               "skipped": sum(r["cached"] for r in self.record.values())},
                  "per_student": {sid: {**self.record.get(sid, {}), "status": r.get("status"),
                                        "score": r.get("score"),
                                        **({"late_penalty": r["late"].get("penalty_points")}
                                           if isinstance(r.get("late"), dict) else {})}
                                  for sid, r in sorted(results.items())}}
        write_json(self.out / "batch.json", report)
        self._tell(report)
        return report

    def _supersede(self, stem: str) -> None:
        """Move a student's files from an older grading (or a half-written pair) to ``superseded/``, so
        the output folder only ever shows the current grading; nothing is deleted but an older copy in
        ``superseded/`` (the result itself is kept in ``history/`` first). No link under the output folder
        is followed (grader.batch.store.move)."""
        stored = read_json(self.out / f"{stem}.json")
        if stored is not None:
            history.archive(self.out, stem, stored)
        for name in (f"{stem}.json", f"{stem}.html", f"gradescope/{stem}", f"{REPLAYS}/{stem}"):
            move(self.out / name, self.out / "superseded" / name)

    def _prune_gradescope(self, current: set[str]) -> None:
        """Move Gradescope exports of students with no current result out of ``gradescope/``."""
        folder = self.out / "gradescope"
        for name, is_folder in entries(folder):
            if is_folder and name not in current:
                move(folder / name, self.out / "superseded" / "gradescope" / name)

    def _current(self, stored: dict) -> bool:
        """True if a stored result was graded with this run's week, seed, grader and hidden set. An older
        one (a rerun with another seed, stopped half-way) is left out of the class files and counted as
        not graded yet, so the gradebook never mixes two gradings."""
        batch = b if isinstance(b := stored.get("batch"), dict) else {}
        hidden_set = h if isinstance(h := batch.get("hidden_set"), dict) else {}
        return (stored.get("week") == self.options.week and stored.get("seed") == self.seed
                and batch.get("grader") == self.grader
                and bool(stored.get("hidden", self.options.hidden)) == self.options.hidden
                and hidden_set.get("digest") == (self.hidden_set or {}).get("digest"))

    def _tell(self, report: dict) -> None:
        if self.options.quiet:
            return
        counts = ", ".join(f"{n} {s}" for s, n in report["counts"].items() if n)
        stream = self.progress.stream
        if self.interrupted:
            stream.write(f"interrupted: {report['students'] - report['incomplete']} of {report['students']} "
                         f"students have results; run the same command again to resume\n")
        for sid, reason in list(report["held_reasons"].items())[:50]:
            stream.write(f"held (yours to sort out, not graded): {printable(sid)}: {printable(reason)}\n")
        if report["missing"]:
            stream.write(f"on the roster with no submission: {len(report['missing'])}\n")
        stream.write(f"week {report['week']}: {counts} ({report['this_run']['skipped']} reused); "
                     f"gradebook {self.out / 'gradebook.csv'}, summary {self.out / 'summary.html'}\n")
        regrade = report["under_load"]
        if regrade:
            names = ", ".join(regrade[:20]) + (", ..." if len(regrade) > 20 else "")
            stream.write(f"graded under load, regrade: {len(regrade)} student(s) got no verdict on a check "
                         f"because this machine was too busy ({names}); run the same command again to grade "
                         f"them again\n")
        stream.flush()
