"""One time budget per grading (issue 30, item 2): the second worker weeks 5-7 open for earlier weeks'
blocks (grader.earlier) charges the grading's one TimeBudget, and the result's `time_budget` counts the
calls and the time of both; the kept wrong version (tests/data/load_wrong/fresh_budget.py, a fresh budget
per session, as before) is caught."""

from __future__ import annotations

import sys
from pathlib import Path

from wrong_submissions import build

import grader.grading as grading
from grader.grading import grade_submission
from grader.sandbox import time_budget
from grader.sandbox.limits import Limits
from grader.sandbox.session import StudentSession

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from load_wrong.fresh_budget import open_session_with_a_fresh_budget  # noqa: E402

MISTAKE = "good_week5_week4_u_ao_reversed"  # a week-4 block of its own: the runs get a second worker
CHECK = "week5.blending.reach_goal"


def grade_counting_sessions(tmp_path: Path, monkeypatch, limits: Limits | None = None) -> tuple[dict, list]:
    made: list[StudentSession] = []
    real = StudentSession.__init__

    def init(self, *args, **kwargs) -> None:
        real(self, *args, **kwargs)
        made.append(self)

    monkeypatch.setattr(StudentSession, "__init__", init)
    result = grade_submission(5, build(MISTAKE, tmp_path), seed=2014, only=CHECK, limits=limits)
    return result, made


def one_budget(result: dict, sessions: list[StudentSession]) -> list[str]:
    """What breaks the one-budget rule in this grading (empty: nothing)."""
    wrong = []
    if len(sessions) != 2:
        wrong.append(f"{len(sessions)} sessions, not the two this submission needs")
    if any(s.budget is not sessions[0].budget for s in sessions):
        wrong.append("a session with a budget of its own")
    calls = sum(s.calls for s in sessions)
    if result["time_budget"]["calls"] != calls:
        wrong.append(f"the result counts {result['time_budget']['calls']} calls of the {calls} made")
    return wrong


def test_the_second_worker_charges_the_gradings_one_budget(tmp_path: Path, monkeypatch) -> None:
    result, sessions = grade_counting_sessions(tmp_path, monkeypatch)
    assert result["checks"][0]["status"] == "passed", result["checks"][0]["message"]
    assert one_budget(result, sessions) == []
    assert sessions[1].calls > 0 and result["time_budget"]["total_seconds"] == Limits().total_seconds


def test_the_wrong_version_with_a_fresh_budget_per_session_is_caught(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setattr(grading, "_open_session", open_session_with_a_fresh_budget)
    result, sessions = grade_counting_sessions(tmp_path, monkeypatch)
    assert "a session with a budget of its own" in one_budget(result, sessions)


def _spent_before_and_in_all(tmp_path: Path, monkeypatch) -> tuple[float, float]:
    """The grading's budget spent when the second worker starts its first run, and spent in all: this
    machine's figures now, from a grading with the default limits."""
    starts: list[tuple[int, float]] = []
    real = StudentSession.start_brain

    def start_brain(self, **fields):
        starts.append((id(self), self.budget.used))
        return real(self, **fields)

    monkeypatch.setattr(StudentSession, "start_brain", start_brain)
    result, sessions = grade_counting_sessions(tmp_path / "measured", monkeypatch)
    monkeypatch.setattr(StudentSession, "start_brain", real)
    assert len(sessions) == 2, "the measuring grading opened one worker"
    before = next(used for session, used in starts if session == id(sessions[1]))
    return before, result["time_budget"]["used_seconds"]


def test_the_total_binds_the_runs_on_the_second_worker(tmp_path: Path, monkeypatch) -> None:
    """With too little to spend, the runs on the second worker end on the grading's total. The workers' CPU
    is read at every call here: the grader reads it every CPU_READ_EVERY seconds of calls, so on a fast,
    idle machine a small total would otherwise be seen only after the runs ended. The total is what the
    loads took on this machine just now plus 40 % of what the runs took: a fixed 0.05 s was used up by
    the first load alone on a loaded machine, where the loads' CPU grows as the runs' does."""
    monkeypatch.setattr(time_budget, "CPU_READ_EVERY", 0.0)
    before, spent = _spent_before_and_in_all(tmp_path, monkeypatch)
    total = before + 0.4 * (spent - before)
    print(f"the loads spent {before:.3f} s, all {spent:.3f} s: a total of {total:.3f} s")
    result, sessions = grade_counting_sessions(tmp_path, monkeypatch, Limits(total_seconds=total))
    check = result["checks"][0]
    print(check["message"])
    # a run that ended before the total ran out keeps its points (with step records a whole run of week 5
    # can take less than 0.05 s of CPU); the run that found the total spent is the timeout
    assert check["status"] == "timeout" and check["points"] < check["max_points"]
    assert f"the submission used up its total time of {total:g} s" in check["message"]
    assert one_budget(result, sessions) == [] and sessions[1].calls > 0
