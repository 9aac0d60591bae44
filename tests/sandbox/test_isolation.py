"""Choosing the isolation: "auto" falls back to a subprocess and says so; "bwrap" refuses to pretend."""

from __future__ import annotations

import os

import pytest
from sandbox_helpers import HONEST, honest_probe, make_submission

from grader.sandbox import isolation
from grader.sandbox.errors import SandboxUnavailable
from grader.sandbox.limits import Limits
from grader.sandbox.session import StudentSession


@pytest.fixture
def no_bwrap(monkeypatch):
    monkeypatch.setattr(isolation, "bwrap_works", lambda: (False, "bubblewrap (bwrap) is not installed"))


def test_auto_falls_back_to_a_subprocess_and_says_what_holds(no_bwrap, shared_dir):
    from sandbox_helpers import PROBES

    with StudentSession(1, make_submission(shared_dir, "_honest"), sandbox="auto", probes="sandbox_probes",
                        extra_paths=(str(PROBES),)) as session:
        assert session.isolation == "subprocess"
        assert "no bubblewrap" in session.isolation_note and "network" in session.isolation_note
        assert honest_probe(session) == pytest.approx(HONEST)


def test_bwrap_requested_but_missing_is_not_a_student_problem(no_bwrap, shared_dir):
    with pytest.raises(SandboxUnavailable, match="not installed"):
        StudentSession(1, make_submission(shared_dir, "_honest"), sandbox="bwrap")


def test_unknown_sandbox_name(shared_dir):
    with pytest.raises(ValueError, match="auto, bwrap or subprocess"):
        StudentSession(1, shared_dir, sandbox="docker")


def test_a_missing_interpreter_is_reported_as_unavailable(monkeypatch, shared_dir):
    from sandbox_helpers import PROBES

    real = isolation.plan_worker

    def broken(*args, **kwargs):
        plan = real(*args, **kwargs)
        plan.argv[0] = "/nonexistent/python"
        return plan

    monkeypatch.setattr(isolation, "plan_worker", broken)
    session = StudentSession(1, make_submission(shared_dir, "_honest"), Limits(), sandbox="subprocess",
                             probes="sandbox_probes", extra_paths=(str(PROBES),))
    with pytest.raises(SandboxUnavailable, match="could not be started"):
        session.load()
    session.close()
    monkeypatch.setattr(isolation, "plan_worker", real)
    with StudentSession(1, make_submission(shared_dir / "again", "_honest"), sandbox="subprocess",
                        probes="sandbox_probes", extra_paths=(str(PROBES),)) as session:
        assert honest_probe(session) == pytest.approx(HONEST)


def test_a_grader_with_many_open_files_still_talks_to_its_worker(shared_dir, mode):
    from sandbox_helpers import PROBES

    held = [os.open(os.devnull, os.O_RDONLY) for _ in range(1100)]  # pipe fds land above FD_SETSIZE
    try:
        with StudentSession(1, make_submission(shared_dir, "_honest"), sandbox=mode,
                            probes="sandbox_probes", extra_paths=(str(PROBES),)) as session:
            assert honest_probe(session) == pytest.approx(HONEST)
    finally:
        for fd in held:
            os.close(fd)


def test_the_subprocess_note_says_what_cannot_be_cleaned(monkeypatch):
    """Issue 10 item 9: the isolation note of subprocess mode names what outlives a grading."""
    monkeypatch.setattr(isolation.os, "geteuid", lambda: 1000)
    as_user = isolation.describe("subprocess")
    assert "System V / POSIX IPC" in as_user and "outlive the grading" in as_user
    monkeypatch.setattr(isolation.os, "geteuid", lambda: 0)
    monkeypatch.setattr(isolation, "_uid_range", lambda: (200_000, 260_000))
    as_root = isolation.describe("subprocess")
    # issue 30 item 3: every folder its uid could write is swept, not a list of four
    assert "System V IPC objects, are removed" in as_root and "any folder of this machine" in as_root
    assert "private HOME and TMPDIR" in as_root
