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

import importlib
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
import traceback
from collections.abc import Callable, Iterable
from multiprocessing.connection import Connection, wait
from pathlib import Path
from typing import Any

from grader.batch.proctree import die_with_parent, exit_reason, kill_tree
from grader.sandbox.leftovers import sweep_scratch

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


def resolve(ref: str) -> GradeFn:
    """Import the function named by :func:`function_ref`."""
    module, _, name = ref.partition(":")
    obj: Any = importlib.import_module(module)
    for part in name.split("."):
        obj = getattr(obj, part)
    return obj


def call_to_reply(fn: GradeFn, task: dict) -> bytes:
    """Run ``fn(task)`` and encode the reply; an exception becomes an error reply, never a raise."""
    try:
        return json.dumps({"ok": True, "value": fn(task)}, allow_nan=False).encode()
    except BaseException as exc:  # noqa: BLE001 - SystemExit from deep inside must not kill the loop silently
        return json.dumps({"ok": False, "message": f"{type(exc).__name__}: {exc}",
                           "traceback": traceback.format_exc(limit=20)}).encode()


def _child_main(ref: str, task_fd: int, reply_fd: int) -> None:
    """Child process: answer tasks until the task pipe closes.

    It runs in its own session (``start_new_session``), so a terminal Ctrl-C reaches only the runner,
    which then stops the children in order.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    die_with_parent()
    tasks, replies = Connection(task_fd, writable=False), Connection(reply_fd, readable=False)
    fn = resolve(ref)
    while True:
        try:
            raw = tasks.recv_bytes()
        except (EOFError, OSError):
            return
        replies.send_bytes(call_to_reply(fn, json.loads(raw)))


class _Slot:
    """One grading process (a plain ``python -m grader.batch.pool`` child) and the task it works on.

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
        self.task: dict | None = None
        self.started = 0.0
        self.deadline = 0.0
        self.done = 0

    def ensure_running(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            return
        self.close()
        task_r, task_w = os.pipe()
        reply_r, reply_w = os.pipe()
        self.scratch = Path(tempfile.mkdtemp(prefix=f"{SCRATCH_PREFIX}{os.getpid()}-"))
        self.scratch.chmod(0o711)     # a sandbox uid must reach its own read-only copy inside
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p),
                   TMPDIR=str(self.scratch))
        # its prints and warnings go to a private log (shown when it crashes), not over the progress line
        self.log = tempfile.TemporaryFile()
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "grader.batch.pool", self.ref, str(task_r), str(reply_w)],
            pass_fds=(task_r, reply_w), start_new_session=True, env=env, stdin=subprocess.DEVNULL,
            stdout=self.log, stderr=subprocess.STDOUT)
        os.close(task_r)
        os.close(reply_w)
        self.send_conn = Connection(task_w, readable=False)
        self.conn = Connection(reply_r, writable=False)
        self.done = 0

    def send(self, task: dict, budget_s: float) -> None:
        self.ensure_running()
        assert self.send_conn is not None
        self.task, self.started = task, time.monotonic()
        self.deadline = self.started + budget_s
        try:
            self.send_conn.send_bytes(json.dumps(task).encode())
        except OSError:   # died between the liveness check and the send: the reply pipe reports it
            pass

    def take(self) -> tuple[dict, float]:
        task, seconds = self.task, time.monotonic() - self.started
        self.task = None
        self.done += 1
        assert task is not None
        return task, seconds

    def close(self, kill: bool = False) -> None:
        if self.proc is not None:
            if kill:
                kill_tree(self.proc.pid)
            elif self.send_conn is not None:
                self.send_conn.close()      # EOF: the child leaves its loop and exits
                self.send_conn = None
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                kill_tree(self.proc.pid)
                self.proc.wait(timeout=5)
        for resource in (self.send_conn, self.conn, self.log):
            if resource is not None:
                resource.close()
        if self.scratch is not None:
            sweep_scratch(self.scratch)
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
    ``tasks`` may be a lazy iterator: it is pulled only when a slot is free.
    """

    def __init__(self, grade_fn: GradeFn | str, jobs: int, budget_s: float, recycle_after: int = 200,
                 ) -> None:
        self.ref = function_ref(grade_fn)
        self.jobs, self.budget_s, self.recycle_after = max(1, jobs), budget_s, recycle_after

    def run(self, tasks: Iterable[dict], on_done: Callable[[dict, dict], None]) -> None:
        sweep_orphans()
        slots = [_Slot(self.ref) for _ in range(self.jobs)]
        pending = iter(tasks)
        exhausted = False
        try:
            while True:
                for slot in slots:
                    if slot.task is None and not exhausted:
                        task = next(pending, None)
                        if task is None:
                            exhausted = True
                        else:
                            slot.send(task, self.budget_s)
                busy = [s for s in slots if s.task is not None]
                if not busy:
                    if exhausted:
                        return
                    continue
                # wake for a reply, a death (EOF on the reply pipe), the nearest deadline, or at least
                # once a second to notice a child that died while a grandchild still holds its pipe
                timeout = max(0.0, min(min(s.deadline for s in busy) - time.monotonic(), 1.0))
                wait([s.conn for s in busy if s.conn is not None], timeout=timeout)
                for slot in busy:
                    outcome = self._poll(slot)
                    if outcome is not None:
                        task, outcome["seconds"] = slot.take()
                        if slot.done >= self.recycle_after:
                            slot.close()
                        on_done(task, outcome)
        finally:
            for slot in slots:
                slot.close(kill=slot.task is not None)

    def _poll(self, slot: _Slot) -> dict | None:
        """The slot's outcome if its task has ended (reply, death or budget), else None."""
        assert slot.conn is not None and slot.proc is not None
        pipe_closed = False
        try:
            if slot.conn.poll():
                reply = json.loads(slot.conn.recv_bytes())
                if reply.get("ok"):
                    return {"status": "ok", "value": reply.get("value"), "message": ""}
                return {"status": "crashed", "value": None,
                        "message": f"the grader failed on this submission: {reply.get('message')}",
                        "traceback": reply.get("traceback", "")}
        except (EOFError, OSError, ValueError):
            pipe_closed = True                        # the child closed its end: it died or is dying
        if pipe_closed:
            try:
                slot.proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                kill_tree(slot.proc.pid)
                slot.proc.wait(timeout=5)
        if slot.proc.poll() is not None:
            message, output = exit_reason(slot.proc.returncode), slot.log_tail()
            slot.close()
            return {"status": "crashed", "value": None, "message": message, "traceback": output}
        if time.monotonic() >= slot.deadline:
            slot.close(kill=True)
            return {"status": "timeout", "value": None,
                    "message": f"grading took longer than {self.budget_s:g} s and was stopped"}
        return None


def sweep_orphans(folder: Path | None = None) -> list[Path]:
    """Sweep the temporary folders of grading processes whose runner is gone (killed with SIGKILL, a
    power cut): each folder name carries the runner's pid."""
    swept = []
    for path in Path(folder or tempfile.gettempdir()).glob(f"{SCRATCH_PREFIX}*-*"):
        pid = path.name[len(SCRATCH_PREFIX):].split("-", 1)[0]
        if pid.isdigit() and not _alive(int(pid)) and path.is_dir():
            sweep_scratch(path)
            swept.append(path)
    return swept


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


if __name__ == "__main__":
    _child_main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
