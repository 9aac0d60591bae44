"""The grading process's side of the pool (``python -m grader.batch.grading_process REF TASK_FD REPLY_FD``).

It answers tasks until the task pipe closes. Everything crossing the pipes is plain JSON, one message per
``send_bytes``:

- runner to grading process: a task (a dict), or ``{"none": true}`` (no next task for you now);
- grading process to runner: a reply ``{"ok": true, "value": ...}`` / ``{"ok": false, "message": ...}``
  for the oldest task it holds, or ``{"want": true}`` (ready to begin the next task).

A grading function may be split in two phases (:func:`overlapped`): the first grades, the second writes
the report. Between them the process asks for its next task and writes the report in a thread; if it
gets a next task, that task's first phase begins meanwhile: the submission is spliced and its sandboxed
worker boots (a separate process, on the other core or in the gaps) while the last one's HTML is
rendered. Each
submission still has its own worker, started only after its own splice; replies leave in task order,
since a report thread is always joined before the process sends anything else.
"""

from __future__ import annotations

import functools
import importlib
import json
import os
import signal
import sys
import threading
import traceback
from collections.abc import Callable
from multiprocessing.connection import Connection
from typing import Any

from grader.batch.proctree import die_with_parent

GradeFn = Callable[[dict], dict]
Finish = Callable[[], dict]
WANT = json.dumps({"want": True}).encode()
NO_TASK = json.dumps({"none": True}).encode()


def overlapped(first_phase: Callable[[dict], Finish]) -> Callable[[GradeFn], GradeFn]:
    """Declare ``first_phase(task) -> finish`` for a grading function ``fn`` with
    ``fn(task) == first_phase(task)()``: a grading process then runs ``finish`` (the report) while the
    next task's first phase begins. ``fn`` itself stays what Dask and the tests call."""
    def declare(fn: GradeFn) -> GradeFn:
        fn.first_phase = first_phase  # type: ignore[attr-defined]
        return fn
    return declare


def resolve(ref: str) -> GradeFn:
    """Import the function named by ``"module:qualname"`` (grader.batch.pool.function_ref)."""
    module, _, name = ref.partition(":")
    obj: Any = importlib.import_module(module)
    for part in name.split("."):
        obj = getattr(obj, part)
    return obj


def call_to_reply(fn: Callable[[], dict]) -> bytes:
    """Run ``fn()`` and encode the reply; an exception becomes an error reply, never a raise."""
    try:
        return json.dumps({"ok": True, "value": fn()}, allow_nan=False).encode()
    except BaseException as exc:  # noqa: BLE001 - SystemExit from deep inside must not kill the loop silently
        return _error_reply(exc)


def _error_reply(exc: BaseException) -> bytes:
    """The reply for an exception being handled (its traceback is the current one)."""
    return json.dumps({"ok": False, "message": f"{type(exc).__name__}: {exc}",
                       "traceback": traceback.format_exc(limit=20)}).encode()


def _receive(tasks: Connection) -> dict | None:
    """The next message from the runner; None once the task pipe is closed."""
    try:
        return json.loads(tasks.recv_bytes())
    except (EOFError, OSError):
        return None


def _first(first_phase: Callable[[dict], Finish], task: dict) -> Finish | bytes:
    """The task's second phase, or its error reply if the first phase raised."""
    try:
        return first_phase(task)
    except BaseException as exc:  # noqa: BLE001 - reported exactly as call_to_reply reports it
        return _error_reply(exc)


def serve(fn: GradeFn, tasks: Connection, replies: Connection) -> None:
    """Answer tasks until the runner closes the task pipe."""
    first_phase = getattr(fn, "first_phase", None)
    writing: threading.Thread | None = None      # the previous task's report, being written
    task = _receive(tasks)
    while task is not None:
        if first_phase is None:
            replies.send_bytes(call_to_reply(functools.partial(fn, task)))
            task = _receive(tasks)
            continue
        finish = _first(first_phase, task)
        if writing is not None:
            writing.join()                    # its reply goes out before anything about this task
            writing = None
        if isinstance(finish, bytes):         # the first phase failed: nothing left to overlap
            replies.send_bytes(finish)
            task = _receive(tasks)
            continue
        replies.send_bytes(WANT)
        # the report begins at once: the runner may take a moment to answer (it stores another result)
        writing = threading.Thread(target=lambda f=finish: replies.send_bytes(call_to_reply(f)),
                                   name="batch-report", daemon=True)
        writing.start()
        following = _receive(tasks)
        if following is None or following.get("none"):
            writing.join()
            writing = None
            task = _receive(tasks) if following is not None else None
            continue
        task = following
    if writing is not None:
        writing.join()


def main(ref: str, task_fd: int, reply_fd: int) -> None:
    """Child process entry. It runs in its own session (``start_new_session``), so a terminal Ctrl-C
    reaches only the runner, which then stops the children in order."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    die_with_parent()
    tasks, replies = Connection(task_fd, writable=False), Connection(reply_fd, readable=False)
    serve(resolve(ref), tasks, replies)
    # Every task is answered and the pool sweeps this process's TMPDIR: skip the interpreter's teardown
    # (60-70 ms of CPU with numpy and jinja2 loaded, at the end of every batch and every recycling).
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
