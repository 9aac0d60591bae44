"""The per-call limit judges the worker's own time (CPU and sleep), never time the machine held it up, and
still ends code that spins (in threads, in a child) or sleeps, and a worker kept stopped, within a stated
bound, in both isolation modes (a saturated machine: tests/grader/test_under_load.py). The kept wrong version
(tests/data/load_wrong/wall_clock.py: the wall clock decides, as before issue 34) times the honest worker
out under the same pause."""

from __future__ import annotations

import sys
import threading
import time
from pathlib import Path

import pytest
from machine_load import Pauser
from sandbox_helpers import HONEST, attack, honest_probe

from grader.sandbox import exposed, runner
from grader.sandbox.errors import MachineStalled, SandboxError, StudentTimeout
from grader.sandbox.isolation import BWRAP
from grader.sandbox.limits import Limits

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from load_wrong.wall_clock import WallClock  # noqa: E402

LIMITS = Limits(call_seconds=1.5, start_seconds=15.0, total_seconds=30.0, stall_seconds=20.0)
PAUSE = 3.0
needs_proc = pytest.mark.skipif(not Path("/proc/self/stat").exists(),
                                reason="no /proc: the clock is blind here (test_a_blind_clock...)")


def paused(call):
    """`call()` with every worker process stopped for PAUSE s, 0.2 s after it began."""
    timer = threading.Timer(0.2, Pauser(seconds=PAUSE).pause_once)
    timer.start()
    try:
        return call()
    finally:
        timer.join()


@needs_proc
@pytest.mark.parametrize("how", ["work", "nap"])
def test_a_worker_paused_mid_call_is_not_charged_for_the_pause(open_one, how):
    """0.6 s of CPU (or of sleep) with a 1.5 s limit, stopped for 3 s in the middle: answered."""
    session = open_one("time_use", LIMITS)
    assert honest_probe(session) == pytest.approx(HONEST)
    before, began = session.seconds_used, time.monotonic()
    if how == "nap":
        value = paused(lambda: session.call("probe", name="nap", args={"seconds": 0.6}))
    else:
        value = paused(lambda: attack(session, how="work", seconds=0.6))
    wall = time.monotonic() - began
    charged = session.seconds_used - before
    print(f"{how}: answered after {wall:.2f} s of wall time, {charged:.2f} s charged (limit 1.5 s)")
    assert value == 0.6
    assert wall > PAUSE  # the pause did hold the call up
    assert charged < 1.2  # 0.6 s of work (or sleep) and the first look's 0.05 s, never the 3 s pause
    assert session.budget.stalls == []


@needs_proc
def test_the_wall_clock_wrong_version_times_the_same_call_out(open_one, monkeypatch):
    """The pause test can fail: with the wall clock deciding, the paused honest call is a timeout."""
    monkeypatch.setattr(runner, "CallClock", WallClock)
    session = open_one("time_use", LIMITS)
    assert honest_probe(session) == pytest.approx(HONEST)
    with pytest.raises(StudentTimeout):
        paused(lambda: attack(session, how="work", seconds=0.6))


def allow_forks(monkeypatch, tmp_path: Path) -> None:
    """The worker's filter without its fork ban, as on a machine with no seccomp filter (macOS, Windows,
    other architectures): the student's code can then start processes (tests/sandbox/test_fork_memory.py)."""
    wrong = tmp_path / "seccomp.py"
    text = exposed.source_of("grader/inside/seccomp.py").read_text()
    wrong.write_text(text.replace("DENY_NEW_PROCESSES = True", "DENY_NEW_PROCESSES = False"))
    real = exposed.source_of
    monkeypatch.setattr(exposed, "source_of",
                        lambda relative: wrong if relative == "grader/inside/seccomp.py" else real(relative))


@pytest.mark.parametrize("how", ["threads", "fork"])
def test_cpu_burnt_in_threads_or_a_child_counts(open_session, mode, how, monkeypatch, tmp_path):
    if how == "threads" and mode == BWRAP:
        pytest.skip("threads are read the same way in both modes: the plain subprocess mode shows it")
    """The parent waits (asleep) while its threads or its forked child spin: the CPU of the whole tree is
    the call's, and the call ends within about its limit."""
    if how == "fork":
        allow_forks(monkeypatch, tmp_path)
    session = open_session("time_use", Limits(call_seconds=1.0, total_seconds=30.0, stall_seconds=20.0))
    began = time.monotonic()
    with pytest.raises(SandboxError) as caught:
        attack(session, how=how)
    wall = time.monotonic() - began
    print(f"{how} in {mode}: {type(caught.value).__name__} after {wall:.2f} s: {caught.value.message}")
    assert isinstance(caught.value, StudentTimeout), caught.value
    assert wall < 1.0 + 2.5 + 5.0  # the limit, the stack dump's bound, and a loaded machine's slack
    assert honest_probe(session) == pytest.approx(HONEST)


@needs_proc
def test_a_worker_stopped_past_the_wall_bound_is_a_stall_never_a_timeout(open_one):
    """A worker the machine keeps stopped is never charged and never waited for past `stall_seconds`
    (grader.grading grades that check again); the next call starts a fresh worker. (The worker cannot
    stop itself: its filter refuses stop signals, tests/sandbox/test_attacks.py.)"""
    limits = Limits(call_seconds=1.0, total_seconds=30.0, stall_seconds=3.0)
    session = open_one("time_use", limits)
    assert honest_probe(session) == pytest.approx(HONEST)
    used, began = session.seconds_used, time.monotonic()
    timer = threading.Timer(0.2, Pauser(seconds=6.0).pause_once)
    timer.start()
    try:
        with pytest.raises(MachineStalled) as caught:
            session.call("probe", name="nap", args={"seconds": 0.5})
        wall = time.monotonic() - began
    finally:
        timer.join()
    print(f"{caught.value.message} after {wall:.2f} s")
    assert limits.stall_seconds <= wall < limits.stall_seconds + 2.0
    assert session.budget.stalls == [caught.value.message] and session.seconds_used - used < 0.5
    assert honest_probe(session) == pytest.approx(HONEST) and session.starts == 2


def test_a_blind_clock_falls_back_on_a_generous_wall_clock(open_one, monkeypatch):
    """Where /proc cannot be read, a sleeping call is ended by the wall clock at BLIND_FACTOR times its
    limit, and the budget says its measure was the wall clock."""
    from grader.sandbox import time_budget, worker_clock

    monkeypatch.setattr(worker_clock, "read", lambda pid: None)
    monkeypatch.setattr(time_budget, "read", lambda pid: None)
    session = open_one("stuck", Limits(call_seconds=0.3, total_seconds=30.0))
    assert honest_probe(session) == pytest.approx(HONEST)
    began = time.monotonic()
    with pytest.raises(StudentTimeout):
        attack(session, how="doze")
    wall = time.monotonic() - began
    assert 0.9 <= wall < 0.9 + 3.0
    assert session.budget.blind and "wall clock" in session.budget.to_json()["measure"]

