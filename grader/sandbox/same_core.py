"""One core for a scenario run's ping-pong between the grading thread and the student's worker.

In a scenario the two processes take turns and never run at once: the grader sends a step's readings and
waits, the worker answers and waits. On two cores every step then wakes the other core and meets cold
caches there. On an idle virtual machine that wake-up is the dearest part of a step: pinned to one core,
a week-6 grading took 0.85 CPU-seconds instead of 1.26, and as much less wall time; on a busy machine the
two cost the same (docs/performance.md, issue 24). So for the length of a run the grading thread keeps to
the core it is on, the worker is asked to join it (brain_start's "cpu"), and the thread's own cores are
given back afterwards.

Only the speed depends on this: the worker may ignore the request (it is untrusted anyway), and where
affinity cannot be set (macOS, Windows, a one-core machine, a container that refuses it) the run goes on
unpinned. SIMIAM_SAME_CORE=0 turns it off (benchmarks compare both ways with it).
"""

from __future__ import annotations

import os
from types import TracebackType


def current_cpu() -> int | None:
    """The core this thread is running on now (Linux: /proc/thread-self/stat), or None."""
    for path in ("/proc/thread-self/stat", "/proc/self/stat"):
        try:
            with open(path, "rb") as stat:
                fields = stat.read().rsplit(b")", 1)[1].split()
            return int(fields[36])  # field 39, "processor", counted from the state (field 3)
        except (OSError, IndexError, ValueError):
            continue
    return None


class SameCore:
    """`with SameCore() as cpu:` keeps this thread on one core for the block; `cpu` is that core (to hand to
    the worker), or None where nothing was pinned. Nothing here raises for want of affinity."""

    def __init__(self) -> None:
        self.cpu: int | None = None
        self._before: set[int] | None = None

    def __enter__(self) -> int | None:
        get, put = getattr(os, "sched_getaffinity", None), getattr(os, "sched_setaffinity", None)
        if get is None or put is None or os.environ.get("SIMIAM_SAME_CORE") == "0":
            return None
        cpu = current_cpu()
        try:
            before = get(0)
            if cpu is None or cpu not in before or len(before) < 2:
                return None
            put(0, {cpu})
        except OSError:
            return None
        self.cpu, self._before = cpu, before
        return cpu

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        if self._before is not None:
            try:
                os.sched_setaffinity(0, self._before)
            except OSError:  # the cores were taken away meanwhile (a cpuset changed): keep what is left
                pass
            self._before = None

