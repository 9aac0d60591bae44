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
import statistics
import threading
import time
from dataclasses import dataclass

_TICKS = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


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
            f"numerics: {_numerics_text()}; load average before {_load_text(load_average())} (1, 5, 15 min)")


def _numerics_text() -> str:
    """The BLAS kernel, threads and numpy SIMD level this process runs (simiam.numerics), in a few words."""
    from simiam.numerics import describe

    seen = describe()
    official = "official" if seen["official"] else "NOT official"
    kernel = seen["kernel"] or "no OpenBLAS"
    return f"{kernel}, {seen['threads']} thread, numpy {seen['numpy_simd']} ({official})"


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


def _children(pid: int) -> list[int]:
    """The pids whose parent is `pid` (every thread's children), from /proc; [] where unknown."""
    out: list[int] = []
    try:
        tasks = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return out
    for tid in tasks:
        try:
            with open(f"/proc/{pid}/task/{tid}/children") as f:
                out.extend(int(c) for c in f.read().split())
        except (OSError, ValueError):
            continue
    return out


def _own_cpu(pid: int) -> tuple[str, float] | None:
    """(start time, user + system CPU seconds) of process `pid` itself (not its reaped children)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rpartition(")")[2].split()
    except OSError:
        return None
    # after the command: state is field 3 of stat(5), utime 14, stime 15, starttime 22
    return fields[19], (int(fields[11]) + int(fields[12])) / _TICKS


def can_follow_children() -> bool:
    """Whether /proc lists each process's children here (Linux with CONFIG_PROC_CHILDREN)."""
    return os.path.exists(f"/proc/{os.getpid()}/task/{os.getpid()}/children")


def descendants_cpu() -> float:
    """CPU seconds the live descendants of this process have used so far (their own, from /proc)."""
    tree = ProcessTreeCPU()
    tree.sweep()
    return sum(tree.seen.values())


class ProcessTreeCPU:
    """Samples, every `interval` seconds in a thread, the CPU time of every descendant of this process.

    `getrusage(RUSAGE_CHILDREN)` misses processes that are not waited for along the whole chain: a
    sandboxed worker killed with its bubblewrap parent never reaches it. The sampler sees them while they
    live, and keeps the last figure of each (pid, start time); what a process spends in its last
    interval before it ends, or a process shorter than one interval, escapes it (/proc counts in ticks
    of 1/CLK_TCK s).
    """

    def __init__(self, interval: float = 0.02) -> None:
        self.interval = interval
        self.seen: dict[tuple[int, str], float] = {}
        self.own_cpu = 0.0  # the sampler thread's own CPU, to be taken off this process's figure
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="process-tree-cpu", daemon=True)

    def start(self) -> None:
        self.sweep()
        self.before = dict(self.seen)
        self._thread.start()

    def stop(self) -> float:
        """Stop sampling; CPU seconds the descendants spent since `start`."""
        self._stop.set()
        self._thread.join()
        self.sweep()
        return sum(cpu - self.before.get(key, 0.0) for key, cpu in self.seen.items())

    def sweep(self) -> None:
        pending = _children(os.getpid())
        while pending:
            pid = pending.pop()
            sample = _own_cpu(pid)
            if sample is not None:
                self.seen[(pid, sample[0])] = sample[1]
            pending.extend(_children(pid))

    def _run(self) -> None:
        began = time.thread_time()
        while not self._stop.wait(self.interval):
            self.sweep()
        self.own_cpu = time.thread_time() - began


class Stopwatch:
    """Measures wall and CPU time of a `with` block into `.usage`.

    Children are counted twice over, and the larger figure kept: by `getrusage(RUSAGE_CHILDREN)` (exact,
    but only for processes waited for along the whole chain) and by a `ProcessTreeCPU` sampler (sees
    every descendant, sandboxed ones too, to within a sampling interval each). Where /proc is missing
    only the first counts.
    """

    def __init__(self, follow_children: bool = True) -> None:
        self._tree = ProcessTreeCPU() if follow_children and can_follow_children() else None

    def __enter__(self) -> Stopwatch:
        if self._tree is not None:
            self._tree.start()
        self._cpu = cpu_seconds()
        self._wall = time.perf_counter()
        return self

    def __exit__(self, *exc: object) -> None:
        wall = time.perf_counter() - self._wall
        me, kids = cpu_seconds()
        me, kids = me - self._cpu[0], kids - self._cpu[1]
        if self._tree is not None:
            kids = max(kids, self._tree.stop())
            me = max(0.0, me - self._tree.own_cpu)
        self.usage = Usage(wall, me, kids)


def median_usage(usages: list[Usage]) -> Usage:
    """The median of each clock over several runs of the same thing."""
    return Usage(statistics.median(u.wall for u in usages), statistics.median(u.cpu_self for u in usages),
                 statistics.median(u.cpu_children for u in usages))


def ratio(value: float, baseline: float) -> float:
    """value / baseline, NaN when the baseline is not positive (a clock too coarse to see it)."""
    return value / baseline if baseline > 0 else float("nan")


def prepare_bytecode(packages: tuple[str, ...] = ("simiam", "grader")) -> str:
    """Compile the bytecode of `packages` where it is missing or stale, and say what was done.

    An installed wheel has its bytecode (pip compiles it at install); an editable checkout gets it on
    first import, unless PYTHONDONTWRITEBYTECODE is set (as on some CI machines), when every fresh
    process compiles every module again, ~0.3 s of CPU that a student never pays. Benchmarks call this
    first, so that they measure what an install runs."""
    import compileall
    import importlib.util
    from pathlib import Path

    total = stale = 0
    for name in packages:
        spec = importlib.util.find_spec(name)
        for folder in (spec.submodule_search_locations or []) if spec else []:
            for source in Path(folder).rglob("*.py"):
                total += 1
                cached = Path(importlib.util.cache_from_source(str(source)))
                if not cached.exists() or cached.stat().st_mtime < source.stat().st_mtime:
                    stale += 1
            compileall.compile_dir(folder, quiet=2)
    flag = os.environ.get("PYTHONDONTWRITEBYTECODE")
    note = f"; PYTHONDONTWRITEBYTECODE={flag} here" if flag else ""
    return (f"bytecode: {stale} of {total} modules of {', '.join(packages)} compiled before measuring "
            f"(an installed wheel has them all{note})")
