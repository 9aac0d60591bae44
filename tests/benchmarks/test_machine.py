"""simiam.machine: the machine line every benchmark prints, and CPU accounting that sees processes
`getrusage(RUSAGE_CHILDREN)` never hears of (a sandboxed worker killed together with its bubblewrap parent).
No timing assertions: only CPU seconds a child provably burned."""

from __future__ import annotations

import os
import resource
import signal
import subprocess
import sys
import time

import pytest

from simiam.machine import (
    Stopwatch,
    Usage,
    can_follow_children,
    load_after_line,
    machine_line,
    median_usage,
    ratio,
)

# A child that starts a grandchild burning `burn` CPU seconds, then sleeping; the child prints the
# grandchild's pid and sleeps. Killing the child with SIGKILL and the grandchild afterwards leaves the
# grandchild unreaped by us: like bubblewrap's worker, its CPU never reaches RUSAGE_CHILDREN.
_TREE = """
import os, sys, time
pid = os.fork()
if pid == 0:
    began = time.process_time()
    while time.process_time() - began < float(sys.argv[1]):
        pass
    time.sleep(60)
    os._exit(0)
print(pid, flush=True)
time.sleep(60)
"""


def test_machine_line_names_cpu_cores_python_sandbox_and_load():
    line = machine_line("bubblewrap")
    assert line.startswith("machine: ")
    assert f"({os.cpu_count()} cores" in line
    assert sys.version.split()[0] in line
    assert "sandbox: bubblewrap" in line
    assert "load average before" in line
    assert "load average after" in load_after_line()


@pytest.mark.skipif(not can_follow_children(), reason="/proc does not list children on this system")
def test_a_grandchild_killed_with_its_parent_is_counted():
    burn = 0.3
    rusage_before = _reaped_children_cpu()
    with Stopwatch() as sw:
        child = subprocess.Popen([sys.executable, "-c", _TREE, str(burn)], stdout=subprocess.PIPE, text=True)
        grandchild = int(child.stdout.readline())
        # wait (by its CPU as the Stopwatch's own sampler saw it, not by the clock) until the sampler has
        # counted nearly all the grandchild was told to burn (/proc counts in ticks of 10 ms, truncated):
        # a fixed pause once it had burned could end before a sampler thread starved on busy cores looked
        deadline = time.monotonic() + 60
        while _sampled(sw, grandchild) < burn - 0.05 and time.monotonic() < deadline:
            time.sleep(0.02)
        child.kill()
        child.wait()
        os.kill(grandchild, signal.SIGKILL)
    assert _reaped_children_cpu() - rusage_before < burn / 2  # the bare rusage figure really misses it...
    assert sw.usage.cpu_children >= burn * 0.8          # ...and the Stopwatch does not


def test_without_the_tree_sampler_only_rusage_counts():
    with Stopwatch(follow_children=False) as sw:
        subprocess.run([sys.executable, "-c", "pass"], check=True)
    assert sw.usage.cpu_children > 0 and sw.usage.wall > 0


def test_median_and_ratio():
    m = median_usage([Usage(1, 2, 3), Usage(3, 4, 5), Usage(2, 3, 100)])
    assert (m.wall, m.cpu_self, m.cpu_children, m.cpu) == (2, 3, 5, 8)
    assert ratio(3.0, 1.5) == 2.0
    assert ratio(1.0, 0.0) != ratio(1.0, 0.0)  # NaN: a baseline too small to divide by


def _sampled(sw: Stopwatch, pid: int) -> float:
    """The CPU seconds of `pid` in the Stopwatch's process-tree sampler's last look at it."""
    return max((cpu for (seen, _start), cpu in list(sw._tree.seen.items()) if seen == pid), default=0.0)


def _reaped_children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def test_prepare_bytecode_compiles_what_is_missing_and_says_so(tmp_path, monkeypatch):
    import importlib.util
    import os
    import sys

    from simiam.machine import prepare_bytecode

    package = tmp_path / "bytecode_probe_pkg"
    (package / "sub").mkdir(parents=True)
    for path in (package / "__init__.py", package / "sub" / "__init__.py", package / "sub" / "mod.py"):
        path.write_text("X = 1\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    sys.modules.pop("bytecode_probe_pkg", None)
    first = prepare_bytecode(("bytecode_probe_pkg",))
    assert first.startswith("bytecode: 3 of 3 modules of bytecode_probe_pkg compiled")
    cached = importlib.util.cache_from_source(str(package / "sub" / "mod.py"))
    assert os.path.exists(cached)
    assert prepare_bytecode(("bytecode_probe_pkg",)).startswith("bytecode: 0 of 3 modules")
