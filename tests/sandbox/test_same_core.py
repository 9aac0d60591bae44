"""One core for a scenario run (grader.sandbox.same_core, issue 24): the grading thread keeps to the core it
is on for the run and gives its cores back after it; the worker, asked in brain_start, joins that core.
Only speed depends on it (docs/performance.md), so each part is checked for doing what it says; a worker
that ignores the request (kept below as the wrong version) is told apart."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from grader.sandbox import same_core
from grader.sandbox.same_core import SameCore, current_cpu
from grader.sandbox.session import RemoteBrain, StudentSession

REPO = Path(__file__).resolve().parents[2]
READINGS = {"t": 0.033, "dt": 0.033, "ticks": [0, 0], "ir_raw": [133, 133, 133, 133, 133]}
pytestmark = pytest.mark.skipif(not hasattr(os, "sched_setaffinity") or len(os.sched_getaffinity(0)) < 2,
                                reason="needs CPU affinity and two cores")


def test_the_block_keeps_this_thread_on_one_of_its_cores_and_gives_them_back():
    before = os.sched_getaffinity(0)
    with SameCore() as cpu:
        assert cpu in before
        assert os.sched_getaffinity(0) == {cpu} and current_cpu() == cpu
    assert os.sched_getaffinity(0) == before


def test_it_gives_the_cores_back_when_the_block_raises():
    before = os.sched_getaffinity(0)
    with pytest.raises(RuntimeError), SameCore():
        raise RuntimeError("a run's own error")
    assert os.sched_getaffinity(0) == before


def test_nothing_is_pinned_when_turned_off_or_on_one_core(monkeypatch):
    before = os.sched_getaffinity(0)
    monkeypatch.setenv("SIMIAM_SAME_CORE", "0")
    with SameCore() as cpu:
        assert cpu is None and os.sched_getaffinity(0) == before
    monkeypatch.delenv("SIMIAM_SAME_CORE")
    one = {min(before)}
    os.sched_setaffinity(0, one)
    try:
        with SameCore() as cpu:  # already on one core: nothing to choose, nothing to give back
            assert cpu is None and os.sched_getaffinity(0) == one
    finally:
        os.sched_setaffinity(0, before)


def test_where_the_core_is_unknown_the_run_goes_on_unpinned(monkeypatch):
    before = os.sched_getaffinity(0)
    monkeypatch.setattr(same_core, "current_cpu", lambda: None)  # /proc unreadable
    with SameCore() as cpu:
        assert cpu is None and os.sched_getaffinity(0) == before


def test_without_affinity_the_run_goes_on_unpinned(monkeypatch):
    monkeypatch.delattr(os, "sched_setaffinity")  # macOS and Windows have none
    with SameCore() as cpu:
        assert cpu is None


def _worker_cores(session: StudentSession) -> set[int]:
    pid = session._worker._worker_pid()  # the worker itself (under bubblewrap, its pid as seen here)
    assert pid is not None
    with open(f"/proc/{pid}/status") as status:
        line = next(ln for ln in status if ln.startswith("Cpus_allowed_list:"))
    cores: set[int] = set()
    for part in line.split(":", 1)[1].strip().split(","):
        low, _, high = part.partition("-")
        cores.update(range(int(low), int(high or low) + 1))
    return cores


class _IgnoringBrain(RemoteBrain):
    """Wrong version kept: never passes the core on, so the worker keeps every core."""

    def step(self, readings):
        self.cpu = None
        return super().step(readings)


@pytest.mark.parametrize("brain, joins", [(RemoteBrain, True), (_IgnoringBrain, False)])
def test_the_worker_joins_the_core_of_the_run(shared_dir, one_mode, brain, joins):
    every = os.sched_getaffinity(0)
    target = max(every)
    with StudentSession(3, REPO / "solutions" / "week3", sandbox=one_mode) as session:
        remote = brain(session, {"goal": [0.5, 0.5], "v": 0.15}, cpu=target)
        command = remote.step(READINGS)
        assert set(command) >= {"vel_r", "vel_l"}
        assert _worker_cores(session) == ({target} if joins else every)
