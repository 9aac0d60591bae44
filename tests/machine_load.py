"""A machine under load, for the tests: busy processes on every core, and the grading's workers paused.

    with Saturated(4):                      # four processes spinning at the grader's own priority
        with Pauser(seconds=3.0, seed=1) as pauser:  # SIGSTOP the workers at random moments, 3 s each
            result = grade_submission(...)
        assert pauser.pauses >= 2

What a busy VM host, a swapping machine or a paused container does to a worker. Only processes this test
process started are touched (its descendants, found in /proc), and only by their pids.
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import threading
import time

# Spins while the process that started it lives: a test run killed mid-module (no __exit__) leaves no
# spinner loading the machine for whatever runs next.
SPIN = "import os, sys\nwhile os.getppid() == int(sys.argv[1]):\n    for _ in range(1_000_000): pass"


class Saturated:
    """`count` processes spinning at full speed until the block ends (then killed by their pids)."""

    def __init__(self, count: int = 4) -> None:
        self.count = count
        self.procs: list[subprocess.Popen] = []

    def __enter__(self) -> Saturated:
        for _ in range(self.count):
            self.procs.append(subprocess.Popen([sys.executable, "-c", SPIN, str(os.getpid())],
                                               stdin=subprocess.DEVNULL))
        return self

    def __exit__(self, *exc: object) -> None:
        for proc in self.procs:
            proc.kill()
        for proc in self.procs:
            proc.wait()

    @property
    def pids(self) -> set[int]:
        return {p.pid for p in self.procs}


def descendants(root: int, leave: set[int]) -> list[int]:
    """Pids of every live descendant of `root` except those in `leave` (and their own descendants)."""
    parents: dict[int, int] = {}
    for entry in os.scandir("/proc"):
        if entry.name.isdigit():
            try:
                with open(f"/proc/{entry.name}/stat", "rb") as stat:
                    fields = stat.read().rsplit(b")", 1)[1].split()
                if fields[0] != b"Z":
                    parents[int(entry.name)] = int(fields[1])
            except (OSError, IndexError, ValueError):
                pass
    children: dict[int, list[int]] = {}
    for pid, parent in parents.items():
        children.setdefault(parent, []).append(pid)
    found, todo = [], [p for p in children.get(root, []) if p not in leave]
    while todo:
        pid = todo.pop()
        found.append(pid)
        todo += [p for p in children.get(pid, []) if p not in leave]
    return found


LOOK_AGAIN = 0.005  # s


class Pauser:
    """A thread that stops every process this test process started (but `leave`) for `seconds`, at random
    moments until the block ends: the first `first` seconds after the start, the next ones `gap` seconds
    after the one before (each drawn uniformly). `pauses`: how many it made (a pause that found no process
    to stop does not count)."""

    def __init__(self, seconds: float = 3.0, seed: int = 0, gap: tuple[float, float] = (1.0, 3.0),
                 first: tuple[float, float] = (0.1, 0.5), leave: set[int] | None = None) -> None:
        self.seconds = seconds
        self.random = random.Random(seed)
        self.gap = gap
        self.first = first
        self.leave = leave or set()
        self.pauses = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="pauser", daemon=True)

    def __enter__(self) -> Pauser:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()

    def _run(self) -> None:
        wait = self.random.uniform(*self.first)
        while not self._stop.wait(wait):
            # a moment that found no worker looks again soon: a grading of 0.2 s is paused once it runs
            wait = self.random.uniform(*self.gap) if self.pause_once() else LOOK_AGAIN

    def pause_once(self) -> bool:
        """Stop the workers now, for `seconds`; False if there was none."""
        stopped = []
        for pid in descendants(os.getpid(), self.leave):
            try:
                os.kill(pid, signal.SIGSTOP)
                stopped.append(pid)
            except (ProcessLookupError, PermissionError):
                pass
        if stopped:
            self.pauses += 1
            time.sleep(self.seconds)
        for pid in stopped:
            try:
                os.kill(pid, signal.SIGCONT)
            except (ProcessLookupError, PermissionError):
                pass
        return bool(stopped)
