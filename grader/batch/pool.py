"""A pool of long-lived grading processes in which any one can be killed without disturbing the others.

Why not ``concurrent.futures.ProcessPoolExecutor``: it cannot stop one hung task. Killing its worker marks
the whole pool broken and fails every other submission in flight, and a worker that dies (out of memory,
segfault in a C extension) does the same. Here each slot owns one grading process (a fresh interpreter,
as with the ``spawn`` start method, but started with ``subprocess`` so it also works inside daemonic Dask
workers) and a private pipe pair:

- tasks and replies cross the pipe as plain JSON (``send_bytes``), never pickles;
- a slot whose task runs past the wall budget has its whole process tree killed (the grading process and
  the sandboxed student workers it started), is reported as ``timeout`` and restarted;
- a process that dies mid-task is reported as ``crashed`` (with its exit signal) and restarted;
- a process may hold two tasks for a moment: it writes one student's report while the next one starts
  (grader.batch.grading_process). If it dies or overruns then, neither is blamed: both are graded again,
  each alone in a fresh process, and only a task that fails alone is reported;
- processes stay warm between submissions (imports and numpy paid once) and are recycled every
  ``recycle_after`` tasks so a slow leak cannot build up over 400 submissions;
- each grading process gets its own temporary folder (``TMPDIR``), where every copy of student code it
  makes lives. Whenever the process ends, is killed (timeout, Ctrl-C, abort) or dies, the pool deletes
  that folder and cleans up after the sandbox uids recorded in it (grader.sandbox.leftovers); a folder
  left by a runner that was itself killed with SIGKILL is swept by the next pool on the machine.

The grading function is passed by reference (``"module:function"``) so the child imports trusted code
itself; it must be a module-level function.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from multiprocessing.connection import Connection, wait
from pathlib import Path
from typing import Any

from grader.batch.grading_process import NO_TASK
from grader.batch.proctree import exit_reason, kill_tree
from grader.sandbox.capabilities import is_root
from grader.sandbox.leftovers import sweep_scratch
from grader.sandbox.runner import kill_uid
from grader.sandbox.workdir import temp_folder

SCRATCH_PREFIX = "simiam-slot-"

GradeFn = Callable[[dict], dict]


def function_ref(fn: GradeFn | str) -> str:
    """``"module:qualname"`` for a module-level function (what a child process can import)."""
    if isinstance(fn, str):
        return fn
    ref = f"{fn.__module__}:{fn.__qualname__}"
    if "<" in ref:
        raise ValueError(f"{ref} is not importable; pass a module-level function")
    return ref


@dataclass
class _InFlight:
    """A task a grading process holds: sent at ``sent``, due by ``deadline``. ``alone`` marks a task run
    again after a failure it shared with another task: no second task may join it, so this time a crash
    or a timeout is certainly its own."""

    task: dict
    sent: float
    deadline: float
    alone: bool = False


class _Slot:
    """One grading process (a plain ``python -m grader.batch.grading_process`` child) and the tasks it holds:
    usually one; two while it writes one submission's report and has begun the next.

    A subprocess rather than ``multiprocessing.Process``: Dask workers are daemonic processes, which
    multiprocessing forbids to have children, and a fresh interpreter never re-imports the caller's
    ``__main__``. The pipe pair is private (not stdin/stdout), so a stray print cannot break the framing.
    """

    def __init__(self, ref: str) -> None:
        self.ref = ref
        self.proc: subprocess.Popen | None = None
        self.send_conn: Connection | None = None
        self.conn: Connection | None = None       # replies; EOF here also means the child died
        self.log: Any = None
        self.scratch: Path | None = None
        self.flight: list[_InFlight] = []         # oldest first: replies come in this order
        self.done = 0

    def ensure_running(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            return
        self.close()
        task_r, task_w = os.pipe()
        reply_r, reply_w = os.pipe()
        self.scratch = Path(tempfile.mkdtemp(prefix=f"{SCRATCH_PREFIX}{os.getpid()}-", dir=_scratch_parent()))
        self.scratch.chmod(0o711)     # a sandbox uid must reach its own read-only copy inside
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p),
                   TMPDIR=str(self.scratch))
        # its prints and warnings go to a private log (shown when it crashes), not over the progress line
        self.log = tempfile.TemporaryFile()
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "grader.batch.grading_process", self.ref, str(task_r), str(reply_w)],
            pass_fds=(task_r, reply_w), start_new_session=True, env=env, stdin=subprocess.DEVNULL,
            stdout=self.log, stderr=subprocess.STDOUT)
        os.close(task_r)
        os.close(reply_w)
        self.send_conn = Connection(task_w, readable=False)
        self.conn = Connection(reply_r, writable=False)
        self.done = 0

    def send(self, task: dict, budget_s: float, alone: bool = False) -> None:
        self.ensure_running()
        now = time.monotonic()
        self.flight.append(_InFlight(task, now, now + budget_s, alone))
        self._write(json.dumps(task).encode())

    def decline(self) -> None:
        """Answer the process's request for a next task: none for now."""
        self._write(NO_TASK)

    def _write(self, data: bytes) -> None:
        try:
            assert self.send_conn is not None
            self.send_conn.send_bytes(data)
        except OSError:   # died since the liveness check: the reply pipe reports it
            pass

    def take(self) -> tuple[dict, float]:
        """The oldest task (its reply has arrived) and the seconds since it was sent."""
        entry = self.flight.pop(0)
        self.done += 1
        return entry.task, time.monotonic() - entry.sent

    def stop(self, kill: bool = False) -> None:
        """Kill the process tree, or close its task pipe (EOF: it leaves its loop and exits); no waiting,
        so several processes can end at once."""
        if self.proc is None:
            return
        if kill:
            kill_tree(self.proc.pid)
        elif self.send_conn is not None:
            self.send_conn.close()
            self.send_conn = None

    def close(self, kill: bool = False) -> None:
        if self.proc is not None:
            self.stop(kill)
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                kill_tree(self.proc.pid)
                self.proc.wait(timeout=5)
        for resource in (self.send_conn, self.conn, self.log):
            if resource is not None:
                resource.close()
        if self.scratch is not None:
            sweep_scratch(self.scratch, kill_uid)
        self.proc, self.send_conn, self.conn, self.log, self.scratch = None, None, None, None, None

    def log_tail(self, limit: int = 4000) -> str:
        """The end of what the grading process printed (for a crash report)."""
        if self.log is None:
            return ""
        try:
            self.log.seek(0, os.SEEK_END)
            self.log.seek(max(0, self.log.tell() - limit))
            return self.log.read().decode("utf-8", "replace")
        except (OSError, ValueError):
            return ""


class WorkerPool:
    """Run ``grade_fn(task)`` for every task, ``jobs`` at a time, each under a wall budget.

    ``on_done(task, outcome)`` is called in the caller's thread as each task ends, where ``outcome`` is
    ``{"status": "ok" | "timeout" | "crashed", "value": dict | None, "message": str, "seconds": float}``.
    ``tasks`` may be a lazy iterator: it is pulled only when a grading process is free or asks for its
    next task (a function split with grader.batch.grading_process.overlapped asks as it starts its
    report), and a free process gets its next task before ``on_done`` stores the last one's result.

    A process that dies or overruns while holding two tasks (one's report, the next one's start) does
    not say which one did it: neither is blamed, and each is graded again in a fresh process, alone.
    """

    def __init__(self, grade_fn: GradeFn | str, jobs: int, budget_s: float, recycle_after: int = 200,
                 ) -> None:
        self.ref = function_ref(grade_fn)
        self.jobs, self.budget_s, self.recycle_after = max(1, jobs), budget_s, recycle_after
        self._pending: Iterator[dict] = iter(())
        self._exhausted = False
        self._again: deque[dict] = deque()      # tasks to grade again, alone

    def run(self, tasks: Iterable[dict], on_done: Callable[[dict, dict], None]) -> None:
        sweep_orphans()
        slots = [_Slot(self.ref) for _ in range(self.jobs)]
        self._pending, self._exhausted, self._again = iter(tasks), False, deque()
        try:
            while True:
                for slot in slots:
                    if not slot.flight:
                        self._fill(slot)
                busy = [s for s in slots if s.flight]
                if not busy:
                    if self._exhausted and not self._again:
                        return
                    continue
                # wake for a reply, a death (EOF on the reply pipe), the nearest deadline, or at least
                # once a second to notice a child that died while a grandchild still holds its pipe
                timeout = max(0.0, min(min(s.flight[0].deadline for s in busy) - time.monotonic(), 1.0))
                wait([s.conn for s in busy if s.conn is not None], timeout=timeout)
                ended: list[tuple[dict, dict]] = []
                for slot in busy:
                    ended.extend(self._poll(slot))
                for slot in slots:              # a free process starts its next task first...
                    if not slot.flight:
                        self._fill(slot)
                for task, outcome in ended:     # ...then the results are stored (files, fsync)
                    on_done(task, outcome)
        finally:
            for slot in slots:
                slot.stop(kill=bool(slot.flight))
            for slot in slots:
                slot.close(kill=bool(slot.flight))

    def _next(self) -> dict | None:
        if self._exhausted:
            return None
        task = next(self._pending, None)
        self._exhausted = task is None
        return task

    def _fill(self, slot: _Slot) -> None:
        """Give an idle process a task: one to grade again alone first, else the next one."""
        if self._again:
            slot.send(self._again.popleft(), self.budget_s, alone=True)
        elif (task := self._next()) is not None:
            slot.send(task, self.budget_s)

    def _offer(self, slot: _Slot) -> None:
        """The process asks for its next task while it writes a report: one if allowed and there is one."""
        alone = any(entry.alone for entry in slot.flight)
        recycle = slot.done + len(slot.flight) >= self.recycle_after
        task = None if alone or recycle or len(slot.flight) > 1 else self._next()
        if task is None:
            slot.decline()
        else:
            slot.send(task, self.budget_s)

    def _poll(self, slot: _Slot) -> list[tuple[dict, dict]]:
        """The tasks of this slot that ended (reply, death or budget), with their outcomes."""
        assert slot.conn is not None and slot.proc is not None
        ended: list[tuple[dict, dict]] = []
        pipe_closed = False
        try:
            while slot.flight and slot.conn.poll():
                message = json.loads(slot.conn.recv_bytes())
                if isinstance(message, dict) and message.get("want") is True:
                    self._offer(slot)
                    continue
                task, seconds = slot.take()
                ended.append((task, {**_reply_outcome(message), "seconds": seconds}))
        except (EOFError, OSError, ValueError):
            pipe_closed = True                        # the child closed its end: it died or is dying
        if not slot.flight:
            if slot.done >= self.recycle_after:
                slot.close()
            return ended
        if pipe_closed:
            try:
                slot.proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                kill_tree(slot.proc.pid)
                slot.proc.wait(timeout=5)
        if slot.proc.poll() is not None:
            outcome = {"status": "crashed", "value": None, "message": exit_reason(slot.proc.returncode),
                       "traceback": slot.log_tail()}
        elif time.monotonic() >= slot.flight[0].deadline:
            slot.stop(kill=True)
            outcome = {"status": "timeout", "value": None,
                       "message": f"grading took longer than {self.budget_s:g} s and was stopped"}
        else:
            return ended
        held, slot.flight = slot.flight, []
        slot.close()
        blamed, again = blame(held, outcome)
        self._again.extend(again)
        return ended + blamed


def blame(held: list[_InFlight], outcome: dict) -> tuple[list[tuple[dict, dict]], list[dict]]:
    """Who a grading process's death or overrun counts against: (tasks with that outcome, tasks to
    grade again alone). Only a task the process held alone is blamed; with two, either may be at fault."""
    if len(held) == 1:
        return [(held[0].task, {**outcome, "seconds": time.monotonic() - held[0].sent})], []
    return [], [entry.task for entry in held]


def _reply_outcome(reply: object) -> dict:
    """The outcome a grading process's reply stands for."""
    if isinstance(reply, dict) and reply.get("ok"):
        return {"status": "ok", "value": reply.get("value"), "message": ""}
    reply = reply if isinstance(reply, dict) else {}
    return {"status": "crashed", "value": None,
            "message": f"the grader failed on this submission: {reply.get('message')}",
            "traceback": reply.get("traceback", "")}

def sweep_orphans(folder: Path | None = None) -> list[Path]:
    """Sweep the temporary folders of grading processes whose runner is gone (killed with SIGKILL, a
    power cut): each folder name carries the runner's pid."""
    swept = []
    for path in Path(folder or _scratch_parent()).glob(f"{SCRATCH_PREFIX}*-*"):
        pid = path.name[len(SCRATCH_PREFIX):].split("-", 1)[0]
        if pid.isdigit() and not _alive(int(pid)) and path.is_dir():
            sweep_scratch(path, kill_uid)
            swept.append(path)
    return swept


def _scratch_parent() -> Path:
    """Where the grading processes' temporary folders go: TMPDIR, or, as root, a shared temporary folder
    when TMPDIR is closed to other users, so that a plain-subprocess worker's uid can enter the copies made
    inside (grader.sandbox.workdir) and the sweep still finds everything a killed process left."""
    return temp_folder(is_root())


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True

