"""Fixtures for the sandbox tests: sessions in each isolation mode on attack submissions."""

from __future__ import annotations

import os
import shutil
import tempfile
import uuid
from pathlib import Path

import pytest
from sandbox_helpers import LIMITS, PROBES, make_submission

from grader.sandbox.isolation import BWRAP, SUBPROCESS, bwrap_works
from grader.sandbox.limits import Limits
from grader.sandbox.session import StudentSession


@pytest.fixture(scope="session", autouse=True)
def private_library_cache():
    """The workers' shared library (grader.sandbox.library) in a folder of this test run: the wrong versions
    some tests expose (the whole simiam package, a weaker seccomp filter) stay out of the user's cache."""
    folder = tempfile.mkdtemp(prefix="simiam-library-cache-test-")
    before = os.environ.get("SIMIAM_CACHE_DIR")
    os.environ["SIMIAM_CACHE_DIR"] = folder
    yield Path(folder)
    if before is None:
        os.environ.pop("SIMIAM_CACHE_DIR", None)
    else:
        os.environ["SIMIAM_CACHE_DIR"] = before
    shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture
def shared_dir():
    """A fresh folder the worker's uid can reach (pytest's own tmp root is reset to 0700 by any concurrent
    pytest run, so the submissions live in their own mkdtemp directory)."""
    base = Path(tempfile.mkdtemp(prefix="simiam-sandbox-test-"))
    base.chmod(0o711)
    yield base
    shutil.rmtree(base, ignore_errors=True)


def _modes() -> list:
    works, why = bwrap_works()
    return [pytest.param(BWRAP, marks=[pytest.mark.sandbox, pytest.mark.skipif(not works, reason=why)]),
            SUBPROCESS]


@pytest.fixture(params=_modes())
def mode(request) -> str:
    """Both isolation modes: for attacks whose outcome depends on the isolation."""
    return request.param


@pytest.fixture
def one_mode() -> str:
    """The mode "auto" picks: for attacks handled by the protocol alone (same in both modes)."""
    return BWRAP if bwrap_works()[0] else SUBPROCESS


def _session_factory(shared_dir: Path, mode: str):
    sessions: list[StudentSession] = []

    def make(attack: str, limits: Limits = LIMITS) -> StudentSession:
        folder = make_submission(shared_dir / uuid.uuid4().hex[:8], attack)
        session = StudentSession(1, folder, limits, sandbox=mode, probes="sandbox_probes",
                                 extra_paths=(str(PROBES),))
        sessions.append(session)
        return session

    return make, sessions


@pytest.fixture
def open_session(shared_dir, mode):
    """open_session(attack, limits) -> a StudentSession on that attack in each mode, closed at teardown."""
    make, sessions = _session_factory(shared_dir, mode)
    yield make
    for session in sessions:
        session.close()


@pytest.fixture
def open_one(shared_dir, one_mode):
    """Like open_session, in the one mode "auto" picks."""
    make, sessions = _session_factory(shared_dir, one_mode)
    yield make
    for session in sessions:
        session.close()
