"""StudentSession: the grader's handle on one submission's sandboxed worker; RemoteBrain over it (Seam 1).

    with StudentSession(3, spliced_dir) as session:
        session.load()                                   # {"modules": {...}, "errors": [...]}
        value = session.call("probe", name="uni_to_diff", args={"v": 0.1, "w": 0.5})
        sim = Simulator(world, RemoteBrain(session, settings), spec=..., dt=...)

The worker reads a private copy of `spliced_dir` (grader.sandbox.workdir), never the folder itself.
`call` returns the worker's JSON value (untrusted: check it with grader.sandbox.validate) or raises
StudentError (the student's code raised; file and line inside the submission), StudentTimeout (per call, or
the grading's total budget is spent; with `file`, `line` and `function` of the student's code that was
still running, read from the worker's stack dump by grader.sandbox.stuck, when it can be known), WorkerDied
(exit, kill, limits, protocol abuse), MachineStalled (a wall bound passed while the student's own time did
not: the machine's fault, never a verdict; grader.grading redoes the check).
Time limits count the worker's own time (grader.sandbox.worker_clock); the grading's total is one
TimeBudget (grader.sandbox.time_budget), which every session of a grading shares (`budget=`). After a kill the
next call starts a fresh worker, unless importing the submission is what killed it: then every call raises
that same WorkerDied without starting again.
"""

from __future__ import annotations

import os
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from grader.inside.answer_bounds import AnswerBudget, OutOfBounds
from grader.inside.caps import (
    FILE_CHARS,
    MAX_ERRORS,
    MAX_MODULES,
    MAX_NAMES,
    MESSAGE_CHARS,
    NAME_CHARS,
    TYPE_CHARS,
    clip,
)
from grader.inside.step_record import StepLayout, layout_for
from grader.sandbox import isolation
from grader.sandbox.capabilities import has_module, with_refused_limits
from grader.sandbox.channel import PortableWorker
from grader.sandbox.errors import MachineStalled, SandboxUnavailable, StudentError, StudentTimeout, WorkerDied
from grader.sandbox.limits import Limits
from grader.sandbox.runner import RequestTooLarge, WorkerProcess
from grader.sandbox.stuck import Stuck, find_stuck
from grader.sandbox.time_budget import CpuMeter, TimeBudget
from grader.sandbox.validate import BadValue
from grader.sandbox.workdir import WorkCopy
from simiam import numerics

_KEEP_OUTPUTS = 8  # output of the last workers of a session shown in feedback
PROBES_PER_REQUEST = 64  # a property check's cases fit in one request (25 or 50 of them, mostly)


class StudentSession:
    """One submission's worker, started lazily, restarted after a kill, always killed on close()."""

    def __init__(self, week: int, spliced_dir: Path | str, limits: Limits | None = None, *,
                 sandbox: str = "auto", probes: str = "grader.inside.probes", probes_file: Path | None = None,
                 extra_paths: tuple[str, ...] = (),
                 loader: str = "simiam.course.loader:load_submission", official: bool = False,
                 budget: TimeBudget | None = None) -> None:
        self.week = int(week)
        self.spliced_dir = Path(spliced_dir).resolve()
        self.limits = limits or Limits()
        self.isolation = _choose(sandbox)
        self._config = {"week": self.week, "probes": probes, "loader": loader}
        self._extra_paths = tuple(str(Path(p).resolve()) for p in extra_paths)
        self._probes_file = probes_file
        self._work: WorkCopy | None = None
        self._library = Path()
        self._uid: int | None = None  # the dedicated uid of this session's workers (root only)
        self._worker: WorkerProcess | None = None
        self._outputs: list[CappedText] = []
        self._load: dict | None = None
        self._load_death: WorkerDied | None = None
        # official: a platform's official grading, whose note never says "local check only"
        self.isolation_note = self._base_note = isolation.describe(self.isolation, official=official)
        self.numerics: dict[str, object] = numerics.checked(None)  # what the worker reports when it starts
        self._spawned: float | None = None  # when a worker was spawned that is not waited for yet
        # the grading's time, shared with every session it opens (limits.total_seconds of own time)
        self.budget = budget or TimeBudget(self.limits.total_seconds, self.limits.total_wall_seconds)
        self._meter: CpuMeter | None = None  # the CPU time of the current worker
        self._records: WorkerProcess | None = None  # the worker whose brain agreed on step records
        self.calls = 0
        self.starts = 0
        self.start_seconds: list[float] = []

    # ---- public ------------------------------------------------------------------------------------
    @property
    def seconds_used(self) -> float:
        """The grading's time charged so far: its workers' CPU time and sleep (every session sharing
        the budget), or the wall time of calls where that cannot be read."""
        return self.budget.used

    def start(self) -> None:
        """Spawn the worker now and return at once: it starts (0.15-0.3 s) while the grader imports its
        checks. The first load() or call() waits for it. Nothing is raised here: a worker that cannot
        start is started again, and its failure raised, by that first call."""
        if self._worker is None and self._load_death is None:
            try:
                self._spawn()
            except Exception:  # noqa: BLE001 - the first call spawns again and raises it where it is handled
                self._spawned = None

    def load(self) -> dict:
        """Load the submission in the worker: {"modules": {stem: names}, "errors": [LoadError JSON]}."""
        self._ensure_worker()
        assert self._load is not None
        return self._load

    def call(self, op: str, timeout: float | None = None, **fields: Any) -> Any:
        """Run `op` in the worker and return its JSON value (see the module docstring for errors)."""
        if op == "load":
            return self.load()
        self._ensure_worker()
        return self._request(op, fields, timeout)

    def start_brain(self, **fields: Any) -> StepLayout | None:
        """`call("brain_start", **fields)`, proposing step records (grader.inside.step_record) for the
        run: their layout if the worker's brain agreed (its signals and IR count are the week's), else
        None (the run's steps are JSON)."""
        layout = _week_layout(self.week)
        if layout is None:
            self.call("brain_start", **fields)
            return None
        value = self.call("brain_start", record=layout.to_json(), **fields)
        self._records = self._worker if value == {"record": True} else None
        return layout if self._records is not None else None

    def brain_step(self, readings: Any, timeout: float | None, layout: StepLayout | None) -> Any:
        """`call("brain_step", readings=readings)`, as step records when `layout` is what `start_brain`
        agreed with this same worker (after a restart, the JSON call says what it always said)."""
        worker = self._worker
        if layout is None or worker is None or worker is not self._records or worker.dead is not None:
            return self.call("brain_step", timeout=timeout, readings=readings)
        return self._request("brain_step", readings, timeout, layout)

    def probe_many(self, probes: list[dict], timeout: float | None = None,
                   budget: AnswerBudget | None = None) -> list[Any]:
        """Run several probes ({"name", "args"} each) in order in one request; per probe, its JSON value
        (untrusted, like call's) or the SandboxError call would have raised for it.

        The answers kept weigh at most `budget` in all (a fresh AnswerBudget if none is given; a property
        check passes one for all its rounds): an answer that does not fit is a BadValue instead, and is
        dropped as soon as it is read (grader.inside.answer_bounds).

        The worker answers each probe as soon as it is done, and each answer gets the per-call limit
        counted from the answer before it: a probe that hangs times out as itself, and the worker is
        then killed as after any timeout. The list stops after a timeout or a dead worker (the probes
        after it were not run); a student error in one probe is that probe's answer, and the worker goes
        on with the next. Every answer is read, so nothing of this request is left for a later call.
        """
        if not probes:
            return []
        budget = budget or AnswerBudget()
        results: list[Any] = []
        todo = [probes[i:i + PROBES_PER_REQUEST] for i in range(0, len(probes), PROBES_PER_REQUEST)]
        while todo:
            chunk = todo.pop(0)
            try:
                self._ensure_worker()
                results += self._stream(chunk, timeout, budget)
            except RequestTooLarge:  # nothing was sent: the same probes in two requests
                half = len(chunk) // 2
                todo[:0] = [chunk[:half], chunk[half:]]
                continue
            except (StudentTimeout, WorkerDied, MachineStalled) as exc:  # no worker, no budget: as call
                return [*results, exc]
            if isinstance(results[-1], (StudentTimeout, WorkerDied, MachineStalled)):
                break
        return results

    def output(self) -> str:
        """What the student's code printed (stdout and stderr together), truncated for feedback."""
        texts = [o.text() for o in self._outputs]
        if self._worker is not None:
            self._worker.output.settle()
            texts.append(self._worker.output.text())
        return "\n".join(t for t in texts if t)

    def take_output(self) -> str:
        """`output()`, and start afresh: what the student's code prints from now on is not in what this
        returned, nor in any later `output()` before the next take. The grader takes the output of the
        visible checks before a hidden check runs, and each hidden check's after it (grader.grading)."""
        texts = [o.text() for o in self._outputs]
        self._outputs.clear()
        if self._worker is not None:
            self._worker.output.settle()
            texts.append(self._worker.output.take())
        return "\n".join(t for t in texts if t)

    def close(self) -> None:
        """Kill the worker and everything it started; remove the private copy of the submission."""
        if self._worker is not None:
            self._retire()
        if self._work is not None:
            self._work.remove()
            self._work = None

    def __enter__(self) -> StudentSession:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ---- internals ---------------------------------------------------------------------------------
    def _ensure_worker(self) -> None:
        if self._load_death is not None:
            raise WorkerDied(self._load_death.message)
        if self._worker is not None and self._worker.dead is None and self._spawned is None:
            return
        if self._spawned is None:
            if self._worker is not None:
                self._retire()
            self._spawn()
        assert self._worker is not None and self._spawned is not None
        began, self._spawned = self._spawned, None
        self._worker.stall_seconds = self.limits.stall_seconds
        try:
            self._worker.wait_ready(self.limits.start_seconds)
        except MachineStalled:
            self._retire()
            self.budget.stalls.append("the worker's start")
            raise
        except (StudentTimeout, WorkerDied) as exc:
            self._retire()
            raise WorkerDied(f"the sandbox did not start: {exc.message}. "
                             f"Output: {self.output()[-500:]}") from None
        self.start_seconds.append(time.monotonic() - began)
        refused = self._worker.ready.get("refused_limits")
        self.isolation_note = with_refused_limits(self._base_note, refused)  # the same after a restart
        self.numerics = numerics.checked(self._worker.ready.get("numerics"))
        self._meter = CpuMeter(self._worker.host_pid)  # the bootstrap's CPU is the grader's, not charged
        try:
            value = self._request("load", {}, None)
        except MachineStalled:
            raise  # _request retired the worker: the next call starts it again
        except (WorkerDied, StudentTimeout) as exc:
            self._load_death = WorkerDied(f"while your files were being imported, {exc.message}")
            raise self._load_death from None
        except StudentError as exc:
            value = {"modules": {}, "errors": [{"file": exc.file, "line": exc.line, "message": str(exc)}]}
        if self._load is None:
            self._load = _check_load(value)

    def _spawn(self) -> None:
        """Start a worker process (not waiting for it to be ready)."""
        self._budget_left()
        began = time.monotonic()
        if self._work is None:
            self._uid = isolation.pick_uid()
            work = WorkCopy(self.spliced_dir, self._uid, in_place=self.isolation == isolation.SUBPROCESS)
            try:  # the only simiam/grader the worker can import (shared, or beside the copy, removed with it)
                self._library = isolation.worker_library(self.isolation, work.path.parent / "library")
            except BaseException:  # kept half-built, the next start would run without a library
                work.remove()
                raise
            self._work = work
        rlimits = self.limits.for_worker(self.budget.left()) \
            if has_module("resource") else None  # none to set: the isolation note says "local check only"
        plan = isolation.plan_worker(
            self.isolation, self._work.path, dict(self._config, rlimits=rlimits), uid=self._uid,
            tmp_bytes=self.limits.tmp_bytes, library=self._library, extra_paths=self._extra_paths,
            probes_file=self._probes_file)
        try:
            # Without bubblewrap: the portable channel, the same on macOS, Windows and Linux (channel.py).
            channel = WorkerProcess if plan.mode == isolation.BWRAP else PortableWorker
            self._worker = channel(plan, self.limits.output_bytes)
        except OSError as exc:  # not the student's doing: the sandbox binary or interpreter cannot run
            raise SandboxUnavailable(f"the worker could not be started: {exc}") from None
        self.starts += 1
        self._spawned = began

    def _request(self, op: str, fields: dict, timeout: float | None, layout: StepLayout | None = None
                 ) -> Any:
        """`op` with `fields` (with `layout`: a brain step whose `fields` are the readings, as records)."""
        assert self._worker is not None
        per_call = timeout or self.limits.call_seconds
        limit = min(per_call, self._budget_left())
        began = time.monotonic()
        self.calls += 1
        self._worker.last_clock = None
        try:
            response = self._worker.request(op, fields, limit) if layout is None \
                else self._worker.step(layout, fields, limit)
        except StudentTimeout:
            raise self._timed_out(limit, per_call) from None
        except MachineStalled as exc:
            raise self._stalled(exc) from None
        finally:
            self._charge(began)
        if response["ok"]:
            return response.get("value")
        raise _student_error(response.get("error"))

    def _stream(self, probes: list[dict], timeout: float | None, budget: AnswerBudget) -> list[Any]:
        """One `probe_many` request and its answers, each read with its own limit (see probe_many)."""
        worker = self._worker
        assert worker is not None
        per_call = timeout or self.limits.call_seconds
        first = worker.send("probe_many", {"probes": probes}, answers=len(probes))
        results: list[Any] = []
        for offset in range(len(probes)):
            try:
                limit = min(per_call, self._budget_left())
            except StudentTimeout as exc:  # the answers still to come must never reach a later call
                worker.kill()
                return [*results, exc]
            began = time.monotonic()
            self.calls += 1
            worker.last_clock = None
            try:
                response = worker.receive(first + offset, limit, "probe")
            except StudentTimeout:  # the worker was killed: the probes after this one never ran
                return [*results, self._timed_out(limit, per_call)]
            except MachineStalled as exc:
                return [*results, self._stalled(exc)]
            except WorkerDied as exc:
                return [*results, exc]
            finally:
                self._charge(began)
            results.append(_kept(response.get("value"), budget) if response["ok"]
                           else _student_error(response.get("error")))
        try:
            worker.no_more_answers()
        except WorkerDied as exc:  # the extra came with the last probe: that probe broke the protocol
            results[-1] = exc
        return results

    def _charge(self, began: float) -> None:
        """Charge the call that began at `began` to the grading's budget (its worker's own time)."""
        worker = self._worker
        clock = worker.last_clock if worker is not None else None
        self.budget.charge(clock, time.monotonic() - began, self._meter)

    def _stalled(self, exc: MachineStalled) -> MachineStalled:
        """A wait the machine held up: recorded in the budget (grader.grading redoes the check)."""
        self.budget.stalls.append(exc.message)
        return exc

    def _timed_out(self, limit: float, per_call: float) -> StudentTimeout:
        """The timeout of a call given `limit` seconds, in words: the per-call limit, or the submission's
        total time when that was less, and where the student's code was stuck (from the stack dump)."""
        if limit < per_call:
            why = f"the submission used up its total time of {self.limits.total_seconds:g} s"
        else:
            why = f"no answer within {limit:g} s, the time limit per call"
        return _timeout(why, self._stuck_at())

    def _stuck_at(self) -> Stuck | None:
        """Where the student's code was when the last call timed out (from the worker's stack dump)."""
        worker = self._worker
        if worker is None or not worker.stack_dump:
            return None
        thread = worker.ready.get("thread")
        folder = str(worker.plan.config.get("submission", ""))
        if worker.plan.mode == isolation.SUBPROCESS:  # the loader resolves it: same view of the files here
            folder = os.path.realpath(folder)
        main_thread = thread if type(thread) is int else None
        return find_stuck(worker.stack_dump, folder, self.spliced_dir, main_thread)

    def _budget_left(self) -> float:
        left = self.budget.left()
        if left <= 0:
            raise StudentTimeout(f"the submission used up its total time of {self.limits.total_seconds:g} s")
        if self.budget.wall >= self.budget.total_wall_seconds:
            raise self._stalled(MachineStalled(
                f"the grading's calls took {self.budget.wall:.0f} s of wall time, more than the "
                f"{self.budget.total_wall_seconds:g} s bound, while the code used {self.budget.used:.1f} s"))
        return left

    def _retire(self) -> None:
        worker, self._worker = self._worker, None
        if self._meter is not None:  # what it used since the last charge, read before it is killed
            self.budget.cpu += 0.0 if self._meter.blind else self._meter.settle()
            self._meter = None
        if worker is not None:
            worker.close()
            self._outputs.append(CappedText(worker.output.text()))
            del self._outputs[:-_KEEP_OUTPUTS]


class CappedText:
    """Output of a worker that has ended."""

    def __init__(self, text: str) -> None:
        self._text = text

    def text(self) -> str:
        return self._text


def _week_layout(week: int) -> StepLayout | None:
    """The step records of a scenario run of `week`: its declared signals and IR count (None for a week
    the course does not have: its steps stay JSON)."""
    from simiam.course.weeks import get_week
    from simiam.signals import week_signals

    try:
        declaration = get_week(week)
    except (KeyError, ValueError, LookupError):
        return None
    return layout_for(week_signals(declaration), len(declaration.spec.ir_mounts))


def _choose(sandbox: str) -> str:
    if sandbox not in ("auto", isolation.BWRAP, isolation.SUBPROCESS):
        raise ValueError(f"sandbox must be auto, bwrap or subprocess, not {sandbox!r}")
    if sandbox == isolation.SUBPROCESS:
        return sandbox
    works, why = isolation.bwrap_works()
    if works:
        return isolation.BWRAP
    if sandbox == isolation.BWRAP:
        raise SandboxUnavailable(why)
    return isolation.SUBPROCESS


def _timeout(why: str, stuck: Stuck | None) -> StudentTimeout:
    """StudentTimeout saying, when known, where the student's code was still running."""
    if stuck is None:
        return StudentTimeout(why)
    message = f"{why}; it was still running at {stuck} (an endless loop or a long wait?)"
    return StudentTimeout(message, stuck.file, stuck.line, stuck.function)


def _kept(value: Any, budget: AnswerBudget) -> Any:
    """`value` if it fits in what the grader keeps of this request's answers, else a BadValue saying so."""
    try:
        return budget.take(value)
    except OutOfBounds as exc:
        return BadValue(f"your code returned {exc}")


def _student_error(error: Any) -> StudentError:
    """Rebuild a student error from the worker's (untrusted) description, keeping only sane fields."""
    if not isinstance(error, dict):
        return StudentError("the worker reported an error it could not describe", "Error")
    kind = clip(error.get("type"), TYPE_CHARS, "Error")
    message = clip(error.get("message"), MESSAGE_CHARS)
    file = clip(error.get("file"), FILE_CHARS) or None
    line = _line(error.get("line"))
    if kind == "NotJSON":
        message = f"your code returned {message}, which cannot be sent to the grader " \
                  "(only numbers, strings, lists and dicts can)"
        kind = ""
    elif kind == "TooLarge":  # grader.inside.answer_bounds
        message = f"your code returned {message}, more than the grader takes from one call"
        kind = ""
    raw = error.get("frames")
    frames = [_frame(f) for f in (raw if isinstance(raw, list) else [])[-20:]]
    return StudentError(message, kind, file, line, frames=[f for f in frames if f])


def _line(value: Any) -> int | None:
    return value if type(value) is int and 0 < value < 10**7 else None


def _frame(f: Any) -> dict | None:
    """One frame of the worker's (untrusted) traceback: file, line, function and code, or None."""
    if not isinstance(f, dict) or not isinstance(f.get("file"), str):
        return None
    line = _line(f.get("line"))
    if line is None:
        return None
    function, code = f.get("function"), f.get("code")
    return {"file": clip(f["file"], FILE_CHARS), "line": line, "function": clip(function, NAME_CHARS),
            "code": clip(code, 200)}


def _check_load(value: Any) -> dict:
    """The worker's load report with every field type-checked and capped (it is sent after student code
    ran, so it may be forged: a million module names, a megabyte of message, a line of 10**300)."""
    if not isinstance(value, dict):
        return {"modules": {}, "errors": [{"file": None, "line": None, "message": "load returned nothing"}]}
    raw: dict = value["modules"] if isinstance(value.get("modules"), dict) else {}
    modules = {clip(name, NAME_CHARS): [clip(n, NAME_CHARS) for n in names[:MAX_NAMES] if isinstance(n, str)]
               for name, names in list(raw.items())[:MAX_MODULES] if isinstance(names, list)}
    errors = [e for e in value.get("errors", []) if isinstance(e, dict)][:MAX_ERRORS] \
        if isinstance(value.get("errors"), list) else []
    errors = [{"file": clip(e.get("file"), FILE_CHARS) or None, "line": _line(e.get("line")),
               "message": clip(e.get("message"), MESSAGE_CHARS, "could not be loaded")} for e in errors]
    return {"modules": modules, "errors": errors}


class RemoteBrain:
    """Seam 1 Brain running the student's supervisor in the session's worker.

    The first step sends `brain_start` with `settings`; each step sends the readings and returns the
    worker's answer as it came: the Simulator checks it (simiam.brain.validate_command, the one place a
    command is validated) and ends the run on an invalid one. Raises the session's errors
    (StudentError, StudentTimeout, WorkerDied), which end the run too (`trace.ending`).
    """

    def __init__(self, session: StudentSession, settings: dict | None = None,
                 step_timeout: float | None = None, cpu: int | None = None,
                 start: tuple[float, float, float] | None = None) -> None:
        self.session = session
        self.settings = settings
        self.start = start  # where the supervisor's estimate starts (None: the week's start, (0, 0, 0))
        self.step_timeout = step_timeout
        self.cpu = cpu  # the core the grading thread keeps to for this run (grader.sandbox.same_core)
        self._started = False
        self._layout: StepLayout | None = None  # the run's step records, once brain_start agreed on them

    def step(self, readings: Mapping[str, Any]) -> Any:
        if not self._started:
            if self.start is None:
                self._layout = self.session.start_brain(settings=self.settings, cpu=self.cpu)
            else:
                self._layout = self.session.start_brain(settings=self.settings, cpu=self.cpu,
                                                        start=[float(c) for c in self.start])
            self._started = True
        return self.session.brain_step(readings, self.step_timeout, self._layout)
