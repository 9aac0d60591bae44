"""StudentSession.start(): the worker boots while the grader imports its checks, and that very worker (not a
second one) serves the first call; a worker that cannot start fails the first call as before."""

from __future__ import annotations

import pytest
from sandbox_helpers import HONEST, honest_probe

from grader.sandbox.errors import WorkerDied
from grader.sandbox.limits import Limits


def test_the_started_worker_is_the_one_that_answers(open_one):
    session = open_one("_honest")
    session.start()
    assert session.starts == 1 and session._worker is not None and session.start_seconds == []
    spawned = session._worker
    session.start()  # twice is once
    assert session.starts == 1 and session._worker is spawned
    assert honest_probe(session) == pytest.approx(HONEST)
    assert session.starts == 1 and session._worker is spawned and len(session.start_seconds) == 1
    assert session.load()["modules"]


def test_a_worker_that_cannot_start_in_time_fails_the_first_call(open_one):
    session = open_one("_honest", Limits(call_seconds=1.5, start_seconds=0.0, total_seconds=30.0))
    session.start()
    with pytest.raises(WorkerDied, match="the sandbox did not start"):
        session.load()

