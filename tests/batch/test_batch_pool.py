"""The grading pool: a hung grading process is killed with everything it started (timeout), a dying
one is reported (crashed), and neither disturbs the other submissions in flight."""

from __future__ import annotations

import base64
import os
import subprocess
import sys
import time
from pathlib import Path

import batch_fake_grader
import pytest
from batch_helpers import HANG_BUDGET_S

from grader.batch.pool import WorkerPool, function_ref
from grader.batch.proctree import kill_tree


def task(sid: str, answer: str) -> dict:
    packed = base64.b64encode(answer.encode()).decode()
    return {"student": sid, "week": 3, "seed": 7, "files": {"answer.txt": packed}}


def run(tasks: list[dict], jobs: int = 2, budget: float = 30.0) -> dict[str, dict]:
    outcomes: dict[str, dict] = {}
    WorkerPool(batch_fake_grader.fake_grade, jobs, budget).run(
        tasks, lambda t, o: outcomes.update({t["student"]: o}))
    return outcomes


def gone(pid: int) -> bool:
    """True once ``pid`` no longer runs (absent, or a zombie awaiting its reaper)."""
    for _ in range(100):
        try:
            with open(f"/proc/{pid}/stat") as stream:
                if stream.read().rsplit(")", 1)[1].split()[0] == "Z":
                    return True
        except OSError:
            return True
        time.sleep(0.05)
    return False


def test_hang_is_killed_with_its_children_and_others_finish(tmp_path: Path) -> None:
    pidfile = tmp_path / "grandchild.pid"
    outcomes = run([task("hang", f"hang {pidfile}"), task("a", "score 3"), task("b", "score 9"),
                    task("c", "crash"), task("d", "score 1")], jobs=2, budget=HANG_BUDGET_S)
    assert outcomes["hang"]["status"] == "timeout"
    assert f"longer than {HANG_BUDGET_S:g} s" in outcomes["hang"]["message"]
    assert gone(int(pidfile.read_text())), "the grading process's child survived the timeout"
    assert outcomes["c"]["status"] == "crashed" and "status 3" in outcomes["c"]["message"]
    assert "about to die" in outcomes["c"]["traceback"]      # what it printed, kept for the instructor
    for sid, score in (("a", 3.0), ("b", 9.0), ("d", 1.0)):
        assert outcomes[sid]["status"] == "ok" and outcomes[sid]["value"]["result"]["score"] == score


def test_exceptions_and_garbage_are_crashes_with_a_reason() -> None:
    outcomes = run([task("r", "raise"), task("g", "garbage"), task("ok", "score 4")], jobs=1)
    assert outcomes["r"]["status"] == "crashed" and "the fake grader broke" in outcomes["r"]["message"]
    assert "RuntimeError" in outcomes["r"]["traceback"]
    assert outcomes["g"]["status"] == "ok" and outcomes["g"]["value"] == {"nope": 1}   # the runner judges it
    assert outcomes["ok"]["value"]["result"]["score"] == 4.0


def test_recycled_workers_give_the_same_results() -> None:
    tasks = [task(f"s{i}", f"score {i}") for i in range(5)]
    outcomes: dict[str, dict] = {}
    WorkerPool(batch_fake_grader.fake_grade, 1, 30, recycle_after=2).run(
        tasks, lambda t, o: outcomes.update({t["student"]: o}))
    assert [outcomes[f"s{i}"]["value"]["result"]["score"] for i in range(5)] == [0.0, 1.0, 2.0, 3.0, 4.0]


def test_function_ref_rejects_local_functions() -> None:
    def local(task: dict) -> dict:
        return task
    assert function_ref(batch_fake_grader.fake_grade) == "batch_fake_grader:fake_grade"
    with pytest.raises(ValueError):
        function_ref(local)


@pytest.mark.parametrize("killer", ["kill_tree", "wrong"])
def test_kill_tree_reaches_grandchildren_and_the_naive_kill_does_not(killer: str, wrong) -> None:
    parent = subprocess.Popen([sys.executable, "-c", "import subprocess, sys, time\n"
                               "c = subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(60)'])\n"
                               "print(c.pid, flush=True); time.sleep(60)"], stdout=subprocess.PIPE, text=True)
    grandchild = int(parent.stdout.readline())
    (kill_tree if killer == "kill_tree" else wrong.kill_only_the_process)(parent.pid)
    parent.wait(timeout=10)
    try:
        assert gone(grandchild) == (killer == "kill_tree")
    finally:
        try:
            os.kill(grandchild, 9)
        except OSError:
            pass
