"""What every benchmark prints next to its figures: the machine it ran on, and wall and CPU clocks.

Raw seconds say little on their own: the same code runs 2-3x faster or slower on another CPU, and on a
shared machine (CI, or several jobs on two cores) the wall clock mostly measures the neighbours. So each
benchmark prints this machine line (CPU model, cores, load average before and after, Python, sandbox),
measures CPU time as well as wall time (its own process and every child process it waited for, through
`getrusage(RUSAGE_CHILDREN)`), and divides its figures by a baseline measured in the same run. The ratios
are what stays comparable between machines and under load.
"""

from __future__ import annotations

import os
import platform
import resource
import time
from dataclasses import dataclass


def cpu_model() -> str:
    """The CPU's model name from /proc/cpuinfo (Linux), else what `platform` knows."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as info:
            for line in info:
                key, _, value = line.partition(":")
                if key.strip() in ("model name", "Hardware", "cpu model") and value.strip():
                    return value.strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown CPU"


def load_average() -> tuple[float, float, float] | None:
    """The 1, 5 and 15 minute load averages, or None where the system does not tell."""
    try:
        return os.getloadavg()
    except (AttributeError, OSError):
        return None


def usable_cores() -> int:
    """Cores this process may run on (the affinity mask), which can be fewer than the machine has."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def _load_text(load: tuple[float, float, float] | None) -> str:
    return "unknown" if load is None else " ".join(f"{x:.2f}" for x in load)


def machine_line(sandbox: str) -> str:
    """One line describing this machine now: CPU, cores, system, Python, `sandbox` (what isolation the
    benchmark used, in words) and the load average before the measurement."""
    cores, usable = os.cpu_count() or 1, usable_cores()
    shared = f"{cores} cores" if usable == cores else f"{cores} cores, {usable} usable"
    return (f"machine: {cpu_model()} ({shared}), {platform.system()} {platform.machine()}, "
            f"{platform.python_implementation()} {platform.python_version()}; sandbox: {sandbox}; "
            f"load average before {_load_text(load_average())} (1, 5, 15 min)")


def load_after_line() -> str:
    """The closing line: the load average after the measurement, and how to read the figures."""
    cores = usable_cores()
    return (f"load average after {_load_text(load_average())}: above {cores} the machine was shared and wall "
            "times grow; CPU seconds and the ratios to the baseline are the figures to compare")


def cpu_seconds() -> tuple[float, float]:
    """(user + system CPU seconds of this process so far, of all its finished and waited-for children)."""
    me = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime, kids.ru_utime + kids.ru_stime


@dataclass
class Usage:
    """Wall seconds and CPU seconds of one measured stretch: this process and its waited-for children."""

    wall: float = 0.0
    cpu_self: float = 0.0
    cpu_children: float = 0.0

    @property
    def cpu(self) -> float:
        """CPU seconds in all processes."""
        return self.cpu_self + self.cpu_children


class Stopwatch:
    """Measures wall and CPU time of a `with` block into `.usage`.

    Children count only once they have ended and been waited for (as `getrusage` does), so measure a
    block that closes the processes it starts.
    """

    def __enter__(self) -> Stopwatch:
        self._cpu = cpu_seconds()
        self._wall = time.perf_counter()
        return self

    def __exit__(self, *exc: object) -> None:
        wall = time.perf_counter() - self._wall
        me, kids = cpu_seconds()
        self.usage = Usage(wall, me - self._cpu[0], kids - self._cpu[1])


def ratio(value: float, baseline: float) -> float:
    """value / baseline, NaN when the baseline is not positive (a clock too coarse to see it)."""
    return value / baseline if baseline > 0 else float("nan")
