"""Same verdict under load (issue 34): graded while four busy processes saturate the cores and every worker
of the grading is stopped for 3 s at random moments, several times per grading, each version's verdict is
the snapshot's (tests/data/verdicts/seed2014.json, as tests/grader/test_checks_fail.py). Code stuck in one
step (an endless loop, a loop of sleeps, a computation far too long) is still a timeout, within its bound.

By default a representative subset (the solutions of weeks 3 and 6 on a scenario check each, week 6's
being the one a pause once cost it, one kept wrong version on a property check, the endless loop); every
check of every solution, stub and kept wrong version of weeks 3-7, and every kind of stuck code, with

    SIMIAM_LOAD_MATRIX=full python -m pytest tests/grader/test_under_load.py -n 0

The kept wrong version of the limit checker (tests/data/load_wrong/wall_clock.py, the wall clock deciding)
loses points under a 3 s pause inside a call, which costs the real one nothing: the comparison can fail.
"""

from __future__ import annotations

import itertools
import json
import os
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import mistakes
import pytest
from machine_load import Pauser, Saturated
from verdict_diff import differences
from verdict_matrix import SNAPSHOT, versions

from grader.grading import grade_submission
from grader.sandbox import runner
from grader.sandbox.limits import Limits
from grader.sandbox.session import RemoteBrain
from grader.sandbox.worker_clock import MACHINE, CallClock, first_wait
from grader.under_load import REDOS, UNDER_LOAD

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from load_wrong.wall_clock import WallClock  # noqa: E402

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="pauses need /proc")

FULL = os.environ.get("SIMIAM_LOAD_MATRIX") == "full"
VERDICTS = json.loads(SNAPSHOT.read_text())["verdicts"]
PAUSE = 3.0
ROOT = Path(__file__).resolve().parents[2]
# label or label::check (that check alone, against its verdict in the snapshot)
SUBSET = ["solutions/week3::week3.go_to_goal.reach_goals", "solutions/week6::week6.laps.left",
          "week3_gains_in_execute::week3.pid.memory"]
EVERY = sorted(label for label, week in versions().items() if 3 <= week <= 7)


@pytest.fixture(scope="module")
def saturated() -> Iterator[Saturated]:
    """Four processes spinning on the (two) cores for the whole module."""
    with Saturated(4) as busy:
        yield busy


def folder_of(label: str, tmp_path: Path) -> tuple[Path, int]:
    week = versions()[label]
    if "/" in label:
        return ROOT / label, week
    return mistakes.build("wrong", label, tmp_path, week), week


def grade_paused(label: str, tmp_path: Path, busy: Saturated, seed: int,
                 first: tuple[float, float] = (0.05, 0.3)) -> tuple[dict, int]:
    """Grade `label` (or `label::check`) as official grading does, under pauses; (result, pauses made)."""
    name, _, check = label.partition("::")
    folder, week = folder_of(name, tmp_path)
    # the first pause early and the next ones close together: a grading of a second's work gets several
    with Pauser(seconds=PAUSE, seed=seed, first=first, gap=(0.2, 1.0), leave=busy.pids) as pauser:
        result = grade_submission(week, folder, seed=2014, hidden=True, only=check or None)
    return result, pauser.pauses


@pytest.mark.parametrize("label", EVERY if FULL else SUBSET)
def test_the_verdict_under_load_and_pauses_is_the_snapshots(label: str, tmp_path: Path, saturated) -> None:
    name, _, check = label.partition("::")
    expected = {k: v for k, v in VERDICTS[name].items() if not check or k == check}
    # a one-check grading can end before the first random pause on a fast machine: grade it again (each
    # grading's verdict must equal the snapshot) until a pause lands, three gradings at most
    for attempt in range(3):
        began = time.monotonic()
        # a grading tried again is paused as soon as its worker runs
        result, pauses = grade_paused(label, tmp_path / str(attempt), saturated,
                                      seed=sum(map(ord, label)) + attempt,
                                      first=(0.05, 0.3) if attempt == 0 else (0.0, 0.01))
        print(f"{label}: {time.monotonic() - began:.1f} s, {pauses} pauses of {PAUSE:g} s, "
              f"time {result.get('time_budget')}")
        assert "under_load" not in result, result["under_load"]
        assert differences(result, expected) == ""
        if pauses >= 1:
            break
    assert pauses >= 1, "no pause landed in three gradings: the test did not test"


def paused_at_step_20(saturated: Saturated, monkeypatch) -> tuple[str, int]:
    """week 3's solution on one scenario check, its worker paused for 3 s at the run's 20th step (so that the
    pause surely lands in a call): (what differs from the snapshot, pauses made)."""
    pauser, steps, real = Pauser(seconds=PAUSE, leave=saturated.pids), itertools.count(), RemoteBrain.step

    def step(self, readings):
        if next(steps) == 20:
            threading.Thread(target=pauser.pause_once).start()
        return real(self, readings)

    monkeypatch.setattr(RemoteBrain, "step", step)
    result = grade_submission(3, ROOT / "solutions" / "week3", seed=2014, hidden=True, only=SETTLE)
    found = differences(result, {SETTLE: VERDICTS["solutions/week3"][SETTLE]})
    print(found or "the snapshot's verdict")
    return found, pauser.pauses


def test_a_pause_inside_a_call_costs_nothing(saturated, monkeypatch) -> None:
    assert paused_at_step_20(saturated, monkeypatch) == ("", 1)


def test_a_wall_clock_limit_loses_points_under_the_same_pause(saturated, monkeypatch) -> None:
    """The wrong version: with the wall clock deciding, the same pause is a timeout against the student."""
    monkeypatch.setattr(runner, "CallClock", WallClock)
    found, pauses = paused_at_step_20(saturated, monkeypatch)
    assert pauses == 1 and "got ['timeout', 0.0]" in found


# The stated bounds of a call that never answers: `call_seconds` of the worker's own time, and at most
# `stall_seconds` of wall time; then the stack dump (runner: the signal taken within DUMP_PENDING_SECONDS of
# the worker's own time, at most `stall_seconds` of wall time, then 2 x DUMP_WAIT_SECONDS to read it).
# Short limits here: the code is stuck at the first step of the check's one run.
STUCK = Limits(call_seconds=0.5, total_seconds=20.0)
DUMP = STUCK.stall_seconds + 2 * runner.DUMP_WAIT_SECONDS
SETTLE = "week3.pid.settle_time"  # a scenario check of one run
STUCK_VERSIONS = ["week3_endless_loop", "week3_sleep_loop", "week3_busy_step"]


@pytest.mark.parametrize("name", STUCK_VERSIONS if FULL else STUCK_VERSIONS[:1])
def test_code_stuck_in_one_step_is_still_a_timeout_within_its_bound(name: str, tmp_path: Path,
                                                                      saturated) -> None:
    folder = mistakes.build("stuck", name, tmp_path, 3, folder_name="week3")
    lines = (folder / "go_to_goal.py").read_text().splitlines()
    line = next(i for i, text in enumerate(lines, 1) if "# STUCK" in text)
    with Pauser(seconds=PAUSE, seed=7, leave=saturated.pids):
        result = grade_submission(3, folder, seed=1, only=SETTLE, limits=STUCK)
    check = result["checks"][0]
    seconds = result["timing"]["checks"][SETTLE]
    print(f"{name}: {check['status']} after {seconds:.1f} s: {check['message'][:160]}")
    assert check["status"] == "timeout" and check["points"] == 0, check["message"]
    assert f"go_to_goal.py:{line} in " in check["message"]
    # a timeout (the student's own time ran out), never a stall; the check's one run ends at its first
    # step, after the worker's start and load (own time, start_seconds at most) and the pauses
    assert seconds < STUCK.start_seconds + STUCK.stall_seconds + DUMP + 2 * PAUSE
    assert result["time_budget"]["used_seconds"] < STUCK.total_seconds


class StallingMachine(CallClock):
    """A machine that holds up the waits numbered `first` to `first + count - 1` of the test (counted from
    1, every wait of every worker) past their wall bound, at once: what `stall_seconds` of a paused
    worker would give, without the wait.

    A wait is counted where it begins: a scenario step's at its first wait (`first_wait`, below: a stalled
    one is 0, so the step goes on to its clock at once), any other wait when its clock is made. A step's
    clock comes after its first wait (`began` given) and judges that same wait."""

    first, count, seen = 0, 0, 0

    def __init__(self, pid, limit, stall_seconds, began=None) -> None:
        super().__init__(pid, limit, stall_seconds, began)
        if began is None:
            StallingMachine.seen += 1
        self.stalls = StallingMachine.stalled()

    @classmethod
    def stalled(cls) -> bool:
        return cls.first <= cls.seen < cls.first + cls.count

    @classmethod
    def first_wait(cls, limit: float) -> float:
        cls.seen += 1
        return 0.0 if cls.stalled() else first_wait(limit)

    def next_wait(self) -> float:
        return 0.0 if self.stalls else super().next_wait()

    def look(self) -> str | None:
        return MACHINE if self.stalls else super().look()


def stalling(monkeypatch, first: int, count: int) -> None:
    monkeypatch.setattr(StallingMachine, "first", first)
    monkeypatch.setattr(StallingMachine, "count", count)
    monkeypatch.setattr(StallingMachine, "seen", 0)
    monkeypatch.setattr(runner, "CallClock", StallingMachine)
    monkeypatch.setattr(runner, "first_wait", StallingMachine.first_wait)


REACH = "week3.go_to_goal.reach_goals"


def test_a_check_the_machine_stalled_once_is_run_again_and_keeps_its_verdict(monkeypatch) -> None:
    stalling(monkeypatch, first=30, count=1)  # one step of the first run
    result = grade_submission(3, ROOT / "solutions" / "week3", seed=2014, hidden=True, only=REACH)
    assert differences(result, {REACH: VERDICTS["solutions/week3"][REACH]}) == ""
    assert result["time_budget"]["stalls"] == 1 and "under_load" not in result


def test_a_check_the_machine_keeps_stalling_says_regrade_never_timeout(monkeypatch) -> None:
    stalling(monkeypatch, first=30, count=10**6)  # every wait after the load
    result = grade_submission(3, ROOT / "solutions" / "week3", seed=2014, hidden=True, only=REACH)
    check = result["checks"][0]
    print(check["message"])
    assert check["status"] == "error" and check["points"] == 0
    assert check["message"].startswith(UNDER_LOAD + ": ") and "timeout" not in check["message"]
    assert result["under_load"]["checks"] == [REACH] and result["under_load"]["regrade"] is True
    assert result["time_budget"]["stalls"] >= REDOS + 1  # each try, and each of its runs, stalled


def test_a_submission_whose_load_keeps_stalling_is_not_charged(monkeypatch) -> None:
    stalling(monkeypatch, first=1, count=10**6)
    result = grade_submission(3, ROOT / "solutions" / "week3", seed=2014, hidden=True, only=REACH)
    assert result["status"] == "invalid" and result["message"].startswith(UNDER_LOAD)
    assert result["under_load"]["checks"] == ["load"]
