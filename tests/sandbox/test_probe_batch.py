"""`probe_many`: several probes in one request, answered one by one (StudentSession.probe_many). Each
probe keeps its own time limit and its own error; a worker that answers a batch with too many, too few,
swapped or forged answers is caught, and nothing of a batch is ever read as the answer to a later call."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest
from sandbox_helpers import HONEST

from grader.sandbox import isolation
from grader.sandbox.errors import StudentError, StudentTimeout, WorkerDied
from grader.sandbox.isolation import SUBPROCESS, WorkerPlan
from grader.sandbox.limits import Limits
from grader.sandbox.session import PROBES_PER_REQUEST, StudentSession

LYING = Path(__file__).resolve().parent / "sandbox_wrong" / "lying_worker.py"
HONEST_PROBE = {"name": "uni_to_diff", "args": {"v": 0.1, "w": 0.5}}


def _attack(fn: str = "attack", **args) -> dict:
    return {"name": "attack", "args": {"fn": fn, **args}}


def test_each_probe_gets_its_own_answer_in_order(open_one):
    session = open_one("_honest")
    session.load()
    before = session.calls
    probes = [{"name": "echo", "args": {"value": k}} for k in range(PROBES_PER_REQUEST + 6)] + [HONEST_PROBE]
    answers = session.probe_many(probes)
    assert answers[:-1] == list(range(PROBES_PER_REQUEST + 6)) and answers[-1] == pytest.approx(HONEST)
    assert session.calls - before == len(probes) and session.starts == 1  # 2 requests, 71 calls
    assert session.call("probe", name="echo", args={"value": "next"}) == "next"  # in step afterwards


def test_a_student_exception_is_the_answer_of_its_probe_and_the_batch_goes_on(open_one):
    session = open_one("base_exception")
    answers = session.probe_many([HONEST_PROBE, _attack(kind="custom"), HONEST_PROBE])
    assert answers[0] == pytest.approx(HONEST) and answers[2] == pytest.approx(HONEST)
    assert isinstance(answers[1], StudentError) and answers[1].type_name == "Boom"
    assert answers[1].file == "differential_drive.py"
    assert session.starts == 1  # no restart: an exception is an answer


def test_a_probe_that_hangs_times_out_as_itself_and_the_rest_never_run(open_one):
    # the short limit only for the batch, where the hang is: loading and the fresh worker get the usual 2 s
    session = open_one("sleep", Limits(call_seconds=2.0, total_seconds=30.0))
    answers = session.probe_many([HONEST_PROBE, HONEST_PROBE, _attack(), HONEST_PROBE], timeout=0.7)
    assert answers[:2] == [pytest.approx(HONEST)] * 2 and len(answers) == 3
    assert isinstance(answers[2], StudentTimeout)
    assert "no answer within 0.7 s, the time limit per call" in answers[2].message
    assert answers[2].file == "differential_drive.py"  # where it was stuck, from the stack dump
    assert session.call("probe", **HONEST_PROBE) == pytest.approx(HONEST)  # a fresh worker answers
    assert session.starts == 2


def test_the_time_limit_is_per_probe_not_per_batch(open_one):
    """Two probes of 0.8 s each take more than the 1.5 s limit of one call together (a sleep is never
    shorter than asked), and each leaves 0.7 s for its answer to come back, far more than the few
    milliseconds that takes with both cores busy (the 0.4 s naps under 0.7 s before left 0.3 s)."""
    session = open_one("_honest", Limits(call_seconds=1.5, total_seconds=30.0))
    answers = session.probe_many([{"name": "nap", "args": {"seconds": 0.8}}] * 2)
    assert answers == [0.8] * 2 and session.starts == 1


def test_the_submissions_total_time_still_binds_inside_a_batch(open_one):
    """The first nap leaves 0.8 s of the 2 s in all for its answer; the second cannot fit in what is left
    (at most 0.8 s for a 1.2 s nap), whatever the machine's load."""
    session = open_one("_honest", Limits(call_seconds=5.0, total_seconds=2.0))
    answers = session.probe_many([{"name": "nap", "args": {"seconds": 1.2}}] * 4)
    assert answers[:1] == [1.2] and len(answers) == 2
    assert isinstance(answers[1], StudentTimeout) and "total time of 2 s" in answers[1].message


def test_a_dead_worker_ends_the_batch_at_the_probe_that_killed_it(open_one):
    session = open_one("os_exit_mid_run")
    answers = session.probe_many([HONEST_PROBE, _attack(), HONEST_PROBE])
    assert answers[0] == pytest.approx(HONEST) and len(answers) == 2
    assert isinstance(answers[1], WorkerDied)
    assert session.call("probe", **HONEST_PROBE) == pytest.approx(HONEST)


# ---- a worker that lies about the batch (tests/sandbox/sandbox_wrong/lying_worker.py) ----------------
@pytest.fixture
def lying_session(shared_dir, monkeypatch):
    """lying_session(lie) -> a session whose worker answers probe_many in the way `lie` names."""
    sessions = []

    def make(lie: str) -> StudentSession:
        def plan(mode, submission, config, **kwargs) -> WorkerPlan:
            return WorkerPlan(mode=SUBPROCESS, argv=[sys.executable, str(LYING), "{}"],
                              env=dict(os.environ), uid=None, note="lying worker", cwd=str(shared_dir),
                              config={"lie": lie})

        monkeypatch.setattr(isolation, "plan_worker", plan)
        session = StudentSession(1, shared_dir, Limits(call_seconds=0.5, total_seconds=30.0),
                                 sandbox=SUBPROCESS)
        sessions.append(session)
        return session

    yield make
    for session in sessions:
        session.close()


THREE = [HONEST_PROBE] * 3


def test_the_lying_worker_answers_honestly_when_told_to(lying_session):
    session = lying_session("honest")
    assert session.probe_many(THREE) == [0, 1, 2]
    assert session.probe_many(THREE) == [0, 1, 2] and session.starts == 1


def test_one_answer_too_many_is_a_protocol_violation_of_the_last_probe(lying_session):
    session = lying_session("too_many")
    answers = session.probe_many(THREE)
    assert answers[:2] == [0, 1] and isinstance(answers[2], WorkerDied)
    assert "more answers than it was asked for" in answers[2].message
    assert session.probe_many(THREE)[:2] == [0, 1] and session.starts == 2  # never the stale extra


def test_one_answer_too_few_is_a_timeout_of_the_unanswered_probe(lying_session):
    session = lying_session("too_few")
    answers = session.probe_many(THREE)
    assert answers[:2] == [0, 1] and isinstance(answers[2], StudentTimeout)
    assert "no answer within 0.5 s" in answers[2].message
    assert session.probe_many(THREE)[:2] == [0, 1] and session.starts == 2


@pytest.mark.parametrize("lie, answered", [("out_of_order", []), ("forged_id", [0])])
def test_swapped_or_forged_ids_kill_the_worker_at_that_answer(lying_session, lie, answered):
    session = lying_session(lie)
    answers = session.probe_many(THREE)
    assert answers[:-1] == answered and isinstance(answers[-1], WorkerDied)
    assert "does not match the question" in answers[-1].message
    session.probe_many(THREE)
    assert session.starts == 2


def test_a_batch_above_the_message_cap_goes_in_several_requests(open_one):
    """Three probes of 1.5 MB each would make a 4.5 MB request, above the cap the worker enforces: the
    grader splits it, and each probe is still answered."""
    session = open_one("_honest")
    big = "x" * 1_500_000
    answers = session.probe_many([{"name": "length", "args": {"value": big}}] * 3)
    assert answers == [len(big)] * 3 and session.starts == 1
