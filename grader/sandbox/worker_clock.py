"""How long a call has really been the student's: the worker's CPU time and its sleep, never the machine's.

A call's time limit is judged on the worker's own time: the CPU time of the worker and every process it
started (all threads; read by the grader from /proc/PID/stat, utime + stime + the reaped children's, by the
host pid, so a PID namespace changes nothing), plus the time it spent asleep (in `time.sleep`, waiting on a
lock or a pipe: the code chose to wait). What is never counted: time the worker was stopped (SIGSTOP, a
debugger, a frozen container: state T), in uninterruptible waits (swapping in, state D), runnable but
waiting for a CPU (the run queue, a VM's steal), and time the grader itself was held up (its wait came back
late). So a loaded or paused machine makes a call take longer by the wall clock, never closer to its limit.

`CallClock` watches one wait: nothing is read while the call is quick (below FIRST_LOOK, as nearly every
call is); after that the worker's processes are read every LOOK_EVERY seconds. Between two looks, the
interval counts as asleep only when the worker was asleep at both ends and the grader was on time; else
only the CPU time used in it counts. A clock that cannot read /proc (Windows, macOS, a /proc hidden from
the grader) is `blind`: it falls back on the wall clock with a generous limit (BLIND_FACTOR times the
stated one), and the grading says so. Past `stall_seconds` of wall time with the worker's own time still
under its limit, the clock gives up: that wait is the machine's fault (MachineStalled), not the student's.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass

FIRST_LOOK = 0.05      # s: a call answered sooner is never read (no cost on the ~1 ms calls of a run)
LOOK_EVERY = 0.1       # s between two looks at a slow call's worker
LATE = 0.25            # s: the grader's own wait came back this much later than asked: it was held up
BLIND_FACTOR = 3.0     # where the worker's time cannot be read, limits are this many times the stated ones
MAX_PROCESSES = 256    # a worker's tree larger than this is read in part (the kernel's NPROC caps it anyway)

STUDENT = "student"    # CallClock.look's verdicts: the student's time is up
MACHINE = "machine"    # the wall bound passed although the student's time did not: the machine stalled

try:
    _TICKS = float(os.sysconf("SC_CLK_TCK"))
except (AttributeError, ValueError, OSError):  # no sysconf (Windows): no /proc either
    _TICKS = 0.0


@dataclass(frozen=True)
class Reading:
    """A look at a worker: the CPU seconds of its tree, and the state of its main process as /proc
    spells it (R running or runnable, S asleep, D uninterruptible, T or t stopped)."""

    cpu: float
    state: str


def _stat(pid: int) -> tuple[str, float, int] | None:
    """(state, CPU seconds of the process and its reaped children, parent pid) from /proc/PID/stat."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
        ticks = int(fields[11]) + int(fields[12]) + int(fields[13]) + int(fields[14])
        return fields[0].decode("ascii", "replace"), ticks / _TICKS, int(fields[1])
    except (OSError, IndexError, ValueError, ZeroDivisionError):
        return None


def _children(pid: int) -> list[int]:
    """The children of every thread of `pid` (/proc/PID/task/TID/children)."""
    found: list[int] = []
    try:
        tasks = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return found
    for tid in tasks[:MAX_PROCESSES]:
        try:
            with open(f"/proc/{pid}/task/{tid}/children", "rb") as f:
                found += [int(c) for c in f.read().split()]
        except (OSError, ValueError):
            pass
    return found


def read(pid: int | None) -> Reading | None:
    """The worker rooted at host pid `pid` (None where it cannot be read).

    CPU counts the whole tree: a student's forks and threads burn the same budget. The state is the main
    process's, except that a child running counts as running (a parent asleep in `wait` while its child
    spins is not asleep), and a stopped main process counts as stopped whatever its children do."""
    if pid is None or _TICKS <= 0:
        return None
    main = _stat(pid)
    if main is None:
        return None
    state, cpu = main[0], main[1]
    todo, seen = _children(pid), 1
    while todo and seen < MAX_PROCESSES:
        child = todo.pop()
        seen += 1
        got = _stat(child)
        if got is None:
            continue
        cpu += got[1]
        if got[0] == "R" and state in ("S", "I"):
            state = "R"
        todo += _children(child)
    return Reading(cpu, state)


def can_read(pid: int | None) -> bool:
    """Whether the worker's time can be read here (else its clocks are blind)."""
    return read(pid) is not None


def _stopped(state: str) -> bool:
    return state in ("T", "t", "D")


def first_wait(limit: float) -> float:
    """How long a wait of `limit` seconds waits for its answer before the worker is first read."""
    return FIRST_LOOK if FIRST_LOOK < limit else limit


class CallClock:
    """The limit of one wait for the worker: `limit` seconds of the worker's own time (CPU and sleep),
    `stall_seconds` of wall time at most (see the module docstring). The caller waits `next_wait()`
    seconds for an answer at a time, and calls `look()` whenever that wait ran out: STUDENT (the limit is
    reached: a timeout), MACHINE (the wall bound passed first: not the student's doing) or None (wait on).

    `pid`: the worker's host pid (the root of its tree); None, or one that cannot be read: blind. `began`:
    when the wait began (`time.monotonic()`), if before the clock was made (a step's wait makes its clock
    only once its first wait, `first_wait`, has passed without an answer); else now."""

    def __init__(self, pid: int | None, limit: float, stall_seconds: float, began: float | None = None
                 ) -> None:
        self.limit = limit
        # never within reach of the limit itself (the looks read the own time up to LOOK_EVERY late)
        self.stall_seconds = max(stall_seconds, 2 * limit + 1.0)
        self.began = self._at = time.monotonic() if began is None else began
        self.pid = pid
        self.blind = False
        self.looked = False
        self.own = 0.0          # the worker's own seconds in this wait, as far as the looks could tell
        self.asleep = 0.0       # of which asleep (the rest is CPU time)
        self.withheld = 0.0     # wall seconds the machine held the worker (or the grader) up
        self._last: Reading | None = None
        self._asked = 0.0       # how long the caller meant to wait before this look

    @property
    def wall(self) -> float:
        return time.monotonic() - self.began

    def next_wait(self) -> float:
        """How long to wait for the answer before the next `look()` (0: look now)."""
        now = time.monotonic()
        if self.blind:
            due = self.began + min(self.limit * BLIND_FACTOR, self.stall_seconds)
        elif not self.looked:
            due = self.began + first_wait(self.limit)
        else:
            due = self._at + LOOK_EVERY
        self._asked = max(0.0, due - now)
        return self._asked

    def look(self) -> str | None:
        """Read the worker and judge the wait so far (see the class docstring)."""
        now = time.monotonic()
        wall = now - self.began
        if self.blind:
            return STUDENT if wall >= min(self.limit * BLIND_FACTOR, self.stall_seconds) else None
        reading = read(self.pid)
        if reading is None:  # no /proc here, or the worker is gone: the wall clock, generously
            self.blind = True
            return self.look()
        span = now - self._at
        late = not self.looked and span > FIRST_LOOK + LATE or self.looked and span > self._asked + LATE
        if self._last is None:
            # the first look: nothing is known of the wait before it but its length and what is seen now
            used = span if not late and not _stopped(reading.state) else 0.0
            self.own = used
            self.asleep = used if reading.state in ("S", "I") else 0.0
        else:
            cpu = max(0.0, reading.cpu - self._last.cpu)
            both_asleep = self._last.state in ("S", "I") and reading.state in ("S", "I")
            gained = max(span, cpu) if both_asleep and not late else cpu
            self.own += gained
            if gained > cpu:
                self.asleep += gained - cpu
        self.withheld = max(0.0, wall - self.own)
        self._last, self._at, self.looked = reading, now, True
        if self.own >= self.limit:
            return STUDENT
        if wall >= self.stall_seconds:
            return MACHINE
        return None

    @property
    def cpu_seen(self) -> float | None:
        """The worker tree's CPU seconds at the last look (None before any, or blind)."""
        return None if self._last is None else self._last.cpu
