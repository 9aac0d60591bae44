"""Issue 10.8: memory is bounded per submission, not per process. RLIMIT_AS binds each process; the worker's
seccomp filter forbids new processes (fork, vfork, clone without CLONE_THREAD), so a submission is one
process and cannot hold more than the stated limit by forking. (No writable cgroup v2 memory controller on
the machines this was built on: the filter is what holds, in both isolation modes.)"""

from __future__ import annotations

from pathlib import Path

import pytest
from sandbox_helpers import LIMITS, attack

from grader.inside import seccomp
from grader.sandbox import exposed
from grader.sandbox.limits import Limits

pytestmark = pytest.mark.skipif(seccomp.program() is None, reason="no seccomp filter for this machine")

MB = 2**20
# Memory is what is limited here, not time: the attack fills up to 1000 MB across four processes, 0.1 s on an
# idle machine but several seconds on a loaded or memory-reclaiming one (a 5 s limit was once missed). The
# call returns as soon as the children report, so the generous limit is spent only if something hangs.
SMALL = Limits(call_seconds=60.0, start_seconds=LIMITS.start_seconds, total_seconds=120.0,
               memory_bytes=400 * MB)


def test_forking_cannot_multiply_the_memory_limit(open_session):
    session = open_session("fork_memory", SMALL)
    seen = attack(session, children=3, mb=250)
    assert seen["error"].startswith("PermissionError")
    assert seen["bytes_held"] <= SMALL.memory_bytes


def test_the_test_sees_forks_multiply_memory(open_session, monkeypatch, tmp_path: Path):
    """The wrong version: the filter without the fork ban (as before). Three children and the worker then
    hold 1000 MB under a 400 MB limit."""
    wrong = tmp_path / "seccomp.py"
    text = exposed.source_of("grader/inside/seccomp.py").read_text()
    wrong.write_text(text.replace("DENY_NEW_PROCESSES = True", "DENY_NEW_PROCESSES = False"))
    real = exposed.source_of
    monkeypatch.setattr(exposed, "source_of",
                        lambda relative: wrong if relative == "grader/inside/seccomp.py" else real(relative))
    session = open_session("fork_memory", SMALL)
    seen = attack(session, children=3, mb=250)
    assert seen["error"] == "" and seen["bytes_held"] == 4 * 250 * MB > SMALL.memory_bytes
