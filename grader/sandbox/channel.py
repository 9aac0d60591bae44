"""The portable channel: the worker as a plain child process on its standard pipes (no sandbox).

Used wherever bubblewrap is not (macOS, a Linux without it, Windows), so the test suite runs it on Linux.
It needs nothing POSIX-only in the grading process: no descriptors passed beyond stdin/stdout/stderr (Windows
cannot pass others), no poll(), no process groups, no /proc, no signals Windows lacks.

- Requests go to the worker's stdin, answers come on its stdout. The worker moves both pipes to private
  descriptors before any student code runs and points its fd 1 at fd 2 (grader.inside.worker), so what the
  student prints lands on stderr, which CappedOutput drains.
- Where the system has poll() and non-blocking pipes (POSIX), the runner's own reads and writes serve (no
  thread hand-off per request). Elsewhere (Windows) a writer thread writes each request (a worker that
  stops reading costs the grader WRITE_SECONDS at most, never a blocked write) and a reader thread queues
  the answers; a deadline is a `get` with a timeout. The emulated Windows of the tests takes this path.
- A call past its deadline kills the worker's whole tree: its process group where the system has them
  (os.killpg), else `taskkill /T /F` (Windows walks the tree by parent pid), then the process itself. On
  Windows a Job object (grader.sandbox.winjob, not tried on Windows) is ended first, which also reaches
  processes that left the tree. As root on Linux the dedicated uid is swept as well (runner.kill_uid).
- Where SIGUSR1 exists (POSIX) the timed-out worker is first asked for a stack dump, which faulthandler
  writes on a pipe of its own passed as one more descriptor (runner.WorkerProcess._dump_stack). Without it
  (Windows) a timeout says only that the time ran out, not where.
"""

from __future__ import annotations

import os
import queue
import select
import shutil
import signal
import subprocess
import threading
import time

from grader.inside.answer_bounds import MAX_ANSWER_BYTES
from grader.inside.protocol import FrameReader
from grader.sandbox import winjob
from grader.sandbox.isolation import WorkerPlan
from grader.sandbox.output import CappedOutput
from grader.sandbox.runner import (
    STALL_SECONDS,
    WorkerProcess,
    _json,
)

WRITE_SECONDS = 5.0        # how long a request may wait for the worker to read it
STDIO = "stdio"            # the worker's config names the channel; the worker sets its pipes up for it
_CREATE_NO_WINDOW = 0x08000000  # Windows: no console window flashes up for taskkill


class PortableWorker(WorkerProcess):
    """WorkerProcess over the worker's standard pipes; threads where poll() is missing (see the module)."""

    def __init__(self, plan: WorkerPlan, output_cap: int) -> None:
        self.plan = plan
        req_r, req_w = os.pipe()
        resp_r, resp_w = os.pipe()
        out_r, out_w = os.pipe()
        # The stack dump's own pipe, passed as one more descriptor: only where SIGUSR1 exists to ask for
        # it, which is where descriptors beyond the standard three can be passed (POSIX).
        self._dump_r, dump_w = os.pipe() if hasattr(signal, "SIGUSR1") else (-1, -1)
        if dump_w >= 0:
            os.set_blocking(self._dump_r, False)
        config = dict(plan.config, channel=STDIO, fd_dump=dump_w if dump_w >= 0 else None)
        argv = plan.argv[:-1] + [_json(config)]
        groups = hasattr(os, "killpg")  # a session of its own only where the grader can kill it whole
        try:
            self.proc = subprocess.Popen(argv, env=plan.env, cwd=plan.cwd, stdin=req_r, stdout=resp_w,
                                         stderr=out_w, start_new_session=groups, close_fds=True,
                                         pass_fds=(dump_w,) if dump_w >= 0 else ())
        except BaseException:
            for fd in (req_w, resp_r, out_r, self._dump_r):
                if fd >= 0:
                    os.close(fd)
            raise
        finally:
            for fd in (req_r, resp_w, out_w, dump_w):
                if fd >= 0:
                    os.close(fd)
        # Windows: a job holds the worker and all it starts, orphans included (winjob; else taskkill)
        self._job = winjob.contain(self.proc) if os.name == "nt" else None
        self.output = CappedOutput(out_r, output_cap)
        self._reader = FrameReader(MAX_ANSWER_BYTES)
        self._writer: _Writer | None = None
        if hasattr(select, "poll") and hasattr(os, "set_blocking"):
            # POSIX: the runner's own poll() and non-blocking writes on these pipes; no thread hand-off
            # per request (two more wake-ups a round trip, which a busy machine makes slow).
            self._req_w, self._resp_r = req_w, resp_r
            os.set_blocking(req_w, False)
            self._answers = select.poll()
            self._answers.register(resp_r, select.POLLIN)
        else:  # Windows: no poll() on pipes, no non-blocking pipe writes: a thread each way
            self._req_w = self._resp_r = -1
            self._chunks: queue.Queue[bytes] = queue.Queue()
            threading.Thread(target=_read_all, args=(resp_r, self._chunks), name="worker-answers",
                             daemon=True).start()
            self._writer = _Writer(req_w)
        self._next_id = 1
        self.started = time.monotonic()
        self.dead: str | None = None
        self.ready: dict = {}
        self.stack_dump = b""
        self.stall_seconds = STALL_SECONDS
        self.last_clock = None
        self.host_pid = None

    def _write(self, data: bytes) -> None:
        if self._writer is None:
            super()._write(data)
        elif not self._writer.write(data, WRITE_SECONDS):
            self._die("it stopped reading requests")

    def _read_answers(self, seconds: float) -> bytes | None:
        if self._writer is None:
            return super()._read_answers(seconds)
        try:
            return self._chunks.get(timeout=max(seconds, 0.001))
        except queue.Empty:
            return None

    def _dump_stack(self) -> bytes:
        """The timed-out worker's stack dump (runner.WorkerProcess._dump_stack, on its own pipe), where
        the system has SIGUSR1; b"" where it has none (Windows)."""
        if self._dump_r < 0:
            return b""
        return super()._dump_stack()

    def _kill_tree(self) -> None:
        if self._job is not None:
            winjob.end(self._job)
            self._job = None
        kill_tree(self.proc)

    def _close_channel(self) -> None:
        if self._writer is not None:
            self._writer.stop()  # the answer pipe is closed by its reader thread, at the worker's end
        super()._close_channel()  # the descriptors this side still holds (closing -1 is a no-op)


def kill_tree(proc: subprocess.Popen) -> str:
    """Kill `proc` and every process it started, on any system; the way it was done, for the tests.

    The process group where the system has them (the worker was started in its own session); else
    `taskkill /T /F`, which walks the tree by parent pid from `proc` while it is still alive; then `proc`
    itself in every case."""
    how = "process itself"
    if hasattr(os, "killpg"):
        try:
            os.killpg(proc.pid, signal.SIGKILL)
            how = "process group"
        except (ProcessLookupError, PermissionError):
            pass
    elif shutil.which("taskkill"):
        try:
            subprocess.run(["taskkill", "/T", "/F", "/PID", str(proc.pid)], stdin=subprocess.DEVNULL,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=30, check=False,
                           creationflags=_CREATE_NO_WINDOW if os.name == "nt" else 0)
            how = "taskkill"
        except (OSError, subprocess.TimeoutExpired):
            pass
    try:
        proc.kill()
    except (ProcessLookupError, OSError):
        pass
    return how


def _read_all(fd: int, chunks: queue.Queue[bytes]) -> None:
    """Reader thread: every chunk of the answer pipe into `chunks`, then b"" at its end."""
    try:
        while True:
            data = os.read(fd, 1 << 16)
            chunks.put(data)
            if not data:
                return
    except OSError:
        chunks.put(b"")
    finally:
        os.close(fd)


class _Writer:
    """A thread that writes requests to the worker's stdin, so a full pipe never blocks the grader."""

    def __init__(self, fd: int) -> None:
        self._fd = fd
        self._todo: queue.Queue[bytes | None] = queue.Queue()
        self._done = threading.Event()
        self._failed = False
        self._thread = threading.Thread(target=self._run, name="worker-requests", daemon=True)
        self._thread.start()

    def write(self, data: bytes, seconds: float) -> bool:
        """True once `data` is all written within `seconds`; False if the pipe broke or stayed full."""
        if self._failed:
            return False
        self._done.clear()
        self._todo.put(data)
        return self._done.wait(seconds) and not self._failed

    def stop(self) -> None:
        self._todo.put(None)

    def _run(self) -> None:
        try:
            while (data := self._todo.get()) is not None:
                try:
                    view = memoryview(data)
                    while view:
                        view = view[os.write(self._fd, view):]
                except OSError:  # BrokenPipeError: the worker is gone
                    self._failed = True
                self._done.set()
        finally:
            os.close(self._fd)
