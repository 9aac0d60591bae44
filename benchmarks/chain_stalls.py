"""How often a batch's grading processes stall, measured in a way the neighbours on a shared machine
barely change.

A grading process and what it started (bubblewrap, the sandboxed worker, the report thread) form a
chain that can keep one core busy. The chain *stalls* when none of its threads is running or waiting
for a core (state R in /proc): it waits for the runner (its next task, a result being stored), for a
process to start, for the disk. Waiting for a core taken by other jobs is not a stall, so the figure is
what the batch itself leaves idle, also at load 8. Linux only (elsewhere nothing is sampled).
"""

from __future__ import annotations

import json
import os
import select
import subprocess
import sys
import time

from simiam.machine import _children  # the /proc walk that ProcessTreeCPU uses


def _states(pid: int) -> list[str]:
    """The state letter of every thread of ``pid`` (empty if it is gone)."""
    states = []
    try:
        tids = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return states
    for tid in tids:
        try:
            with open(f"/proc/{pid}/task/{tid}/stat", "rb") as stream:
                states.append(stream.read().rsplit(b")", 1)[1].split()[0].decode())
        except (OSError, IndexError):
            continue
    return states


class ChainStalls:
    """Samples, every ``interval`` seconds, whether each child process of this one (a grading process)
    and its descendants have a thread running or runnable. The sampler is a separate process, so it
    neither holds this process's GIL (the runner's) nor hides its CPU: ``own_cpu`` is to be taken off."""

    def __init__(self, interval: float = 0.005) -> None:
        self.interval = interval
        self.own_cpu = 0.0
        self._proc: subprocess.Popen | None = None

    def start(self) -> None:
        self._proc = subprocess.Popen([sys.executable, __file__, str(os.getpid()), str(self.interval)],
                                      stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def stop(self) -> float:
        """Stop sampling; the fraction of samples in which a chain stalled (NaN if none were taken)."""
        assert self._proc is not None
        out, _ = self._proc.communicate("", timeout=30)
        figures = json.loads(out)
        self.own_cpu = figures["cpu"]
        return figures["stalled"] / figures["samples"] if figures["samples"] else float("nan")


def sample(runner: int, me: int, counts: dict[str, int]) -> None:
    """One look at every chain below ``runner`` (except this sampler)."""
    for chain in _children(runner):
        if chain == me:
            continue
        pending, runnable = [chain], False
        while pending and not runnable:
            pid = pending.pop()
            runnable = "R" in _states(pid)
            pending.extend(_children(pid))
        counts["samples"] += 1
        counts["stalled"] += not runnable


def main(runner: int, interval: float) -> None:
    """Sample until stdin closes, then print the counts and this process's CPU as JSON."""
    counts = {"samples": 0, "stalled": 0}
    while not select.select([sys.stdin], [], [], interval)[0]:
        sample(runner, os.getpid(), counts)
    print(json.dumps({**counts, "cpu": time.process_time()}))


if __name__ == "__main__":
    main(int(sys.argv[1]), float(sys.argv[2]))
