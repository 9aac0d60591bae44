"""Grading processes overlap one submission's report with the next submission's start
(grader.batch.grading_process): replies stay in order and never mix, a failure while a process holds two
tasks is blamed on neither (each is graded again alone), and the pool hands out work without waiting for
results to be stored."""

from __future__ import annotations

import base64
import json
import threading
from collections.abc import Callable, Iterator
from multiprocessing import Pipe
from pathlib import Path

import batch_fake_grader
import batch_overlap_grader
import pytest
from batch_helpers import HANG_BUDGET_S

from grader.batch import pool
from grader.batch.grading_process import NO_TASK, serve
from grader.batch.pool import WorkerPool


def task(sid: str, answer: str) -> dict:
    packed = base64.b64encode(answer.encode()).decode()
    return {"student": sid, "week": 3, "seed": 7, "files": {"answer.txt": packed}}


def run(tasks: list[dict], fn: Callable = batch_overlap_grader.overlap_grade, jobs: int = 1,
        budget: float = 60.0, recycle_after: int = 200) -> dict[str, dict]:
    outcomes: dict[str, dict] = {}
    WorkerPool(fn, jobs, budget, recycle_after).run(tasks, lambda t, o: outcomes.update({t["student"]: o}))
    return outcomes


@pytest.mark.parametrize("fn", ["overlap_grade", "serial_grade"])
def test_a_report_is_written_while_the_next_submission_begins(tmp_path: Path, fn: str) -> None:
    """The first student's report waits for the second student's first phase (a file it creates): it
    appears only if the process began the second task before finishing the first's report."""
    marker = tmp_path / "second-began"
    outcomes = run([task("a", f"report-waits {marker}"), task("b", f"mark {marker}"), task("c", "score 2")],
                   fn=getattr(batch_overlap_grader, fn))
    assert [outcomes[s]["status"] for s in "abc"] == ["ok", "ok", "ok"]
    message = outcomes["a"]["value"]["result"]["message"]
    assert message == ("overlapped" if fn == "overlap_grade" else "the next task never began")


def test_replies_stay_with_their_students_when_a_report_is_slow(tmp_path: Path) -> None:
    """a's report ends long after b's first phase: each student still gets their own result and page."""
    marker = tmp_path / "b-began"
    answers = {"a": f"report-waits {marker} 1.5", "b": f"mark {marker}"}
    answers |= {f"s{i}": f"score {i}" for i in range(5)}
    outcomes = run([task(s, a) for s, a in answers.items()], jobs=2)
    for sid in answers:
        value = outcomes[sid]["value"]
        assert outcomes[sid]["status"] == "ok" and value["html"] == f"<p>{sid}</p>"
        assert value["result"]["submission"] == sid
    assert [outcomes[f"s{i}"]["value"]["result"]["score"] for i in range(5)] == [0.0, 1.0, 2.0, 3.0, 4.0]


@pytest.mark.parametrize("policy", ["blame", "wrong"])
def test_a_death_while_holding_two_blames_the_one_that_dies_alone(tmp_path: Path, monkeypatch, wrong,
                                                                  policy: str) -> None:
    """b's first phase kills the process while a's report is still being written. Only b may be blamed:
    both are graded again alone, and only b dies again."""
    if policy == "wrong":
        monkeypatch.setattr(pool, "blame", wrong.blame_the_oldest)
    calls = tmp_path / "calls"
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    marker = tmp_path / "b-began"
    outcomes = run([task("a", f"report-waits {marker} 3"), task("b", f"first-crash {marker}"),
                    task("c", "score 7")])
    if policy == "wrong":
        assert outcomes["a"]["status"] == "crashed"          # what the test catches
        return
    assert outcomes["a"]["status"] == "ok" and outcomes["a"]["value"]["result"]["message"] == "overlapped"
    assert outcomes["b"]["status"] == "crashed" and "status 4" in outcomes["b"]["message"]
    assert outcomes["c"]["value"]["result"]["score"] == 7.0
    assert sorted(calls.read_text().split()) == ["a", "a", "b", "b", "c"]


def test_a_report_that_kills_the_process_is_blamed_on_its_own_student(tmp_path: Path,
                                                                      monkeypatch) -> None:
    calls = tmp_path / "calls"
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    marker = tmp_path / "b-began"
    outcomes = run([task("a", f"report-crash {marker}"), task("b", f"mark {marker}")])
    assert outcomes["a"]["status"] == "crashed" and "status 3" in outcomes["a"]["message"]
    assert outcomes["b"]["status"] == "ok" and outcomes["b"]["value"]["result"]["score"] == 5.0
    assert sorted(calls.read_text().split()) == ["a", "a", "b", "b"]


def test_a_hung_report_times_out_alone_and_the_next_student_is_graded(tmp_path: Path) -> None:
    outcomes = run([task("a", "report-hang"), task("b", "score 6")], budget=HANG_BUDGET_S)
    assert outcomes["a"]["status"] == "timeout"
    assert f"longer than {HANG_BUDGET_S:g} s" in outcomes["a"]["message"]
    assert outcomes["b"]["status"] == "ok" and outcomes["b"]["value"]["result"]["score"] == 6.0


def test_first_phase_errors_and_recycling() -> None:
    outcomes = run([task("r", "first-raise")] + [task(f"s{i}", f"score {i}") for i in range(5)],
                   recycle_after=2)
    assert outcomes["r"]["status"] == "crashed" and "the first phase broke" in outcomes["r"]["message"]
    assert "RuntimeError" in outcomes["r"]["traceback"]
    assert [outcomes[f"s{i}"]["value"]["result"]["score"] for i in range(5)] == [0.0, 1.0, 2.0, 3.0, 4.0]


def test_a_free_process_gets_its_next_task_before_the_result_is_stored() -> None:
    """Storing a result (two files, fsync) happens while the grading process already works on the next
    submission: when on_done runs for task i, task i+1 has been handed out."""
    pulled: list[str] = []

    def tasks() -> Iterator[dict]:
        for i in range(4):
            pulled.append(f"s{i}")
            yield task(f"s{i}", f"score {i}")

    seen: dict[str, list[str]] = {}
    WorkerPool(batch_fake_grader.fake_grade, 1, 30.0).run(
        tasks(), lambda t, _o: seen.update({t["student"]: list(pulled)}))
    assert seen["s0"] == ["s0", "s1"] and seen["s2"] == ["s0", "s1", "s2", "s3"]


def test_the_grading_process_asks_for_its_next_task_between_the_phases() -> None:
    """The wire protocol, in this process: task, want, next task, the first reply, want, none, reply."""
    task_r, task_w = Pipe(duplex=False)
    reply_r, reply_w = Pipe(duplex=False)
    server = threading.Thread(target=serve, args=(batch_overlap_grader.overlap_grade, task_r, reply_w))
    server.start()

    def received() -> dict:
        assert reply_r.poll(30), "the grading process said nothing"
        return json.loads(reply_r.recv_bytes())

    task_w.send_bytes(json.dumps(task("a", "score 1")).encode())
    assert received() == {"want": True}
    task_w.send_bytes(json.dumps(task("b", "score 2")).encode())
    assert received()["value"]["result"]["submission"] == "a"
    assert received() == {"want": True}
    task_w.send_bytes(NO_TASK)
    assert received()["value"]["result"]["submission"] == "b"
    task_w.send_bytes(json.dumps(task("c", "first-raise")).encode())
    failed = received()
    assert failed["ok"] is False and "the first phase broke" in failed["message"]   # no want before it
    task_w.close()
    server.join(30)
    assert not server.is_alive()
