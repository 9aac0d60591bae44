"""Fixtures for the sandbox tests: attack submissions, sessions in each isolation mode, the honest answer."""

from __future__ import annotations

import os
import shutil
import tempfile
import uuid
from pathlib import Path

import pytest

from grader.sandbox.isolation import BWRAP, SUBPROCESS, bwrap_works
from grader.sandbox.limits import Limits
from grader.sandbox.session import StudentSession

ATTACKS = Path(__file__).resolve().parents[1] / "data" / "attacks"
PROBES = Path(__file__).resolve().parent / "probe_fixture"
LIMITS = Limits(call_seconds=1.5, start_seconds=15.0, total_seconds=30.0)
R, L = 0.0325, 0.09925
HONEST = [(2 * 0.1 + 0.5 * L) / (2 * R), (2 * 0.1 - 0.5 * L) / (2 * R)]
AS_ROOT = os.geteuid() == 0


@pytest.fixture
def shared_dir():
    """A fresh folder the worker's uid can reach (pytest's own tmp root is reset to 0700 by any concurrent
    pytest run, so the submissions live in their own mkdtemp directory)."""
    base = Path(tempfile.mkdtemp(prefix="simiam-sandbox-test-"))
    base.chmod(0o711)
    yield base
    shutil.rmtree(base, ignore_errors=True)


def make_submission(base: Path, attack: str) -> Path:
    """The honest week-1 files with the attack's files laid over them, readable by the worker's uid."""
    folder = base / f"sub-{attack}"
    folder.mkdir(parents=True)
    for source in (ATTACKS / "_honest", ATTACKS / attack):
        for file in source.glob("*.py"):
            shutil.copy(file, folder / file.name)
    for path in (folder, *folder.iterdir()):
        path.chmod(0o755 if path.is_dir() else 0o644)
    return folder


def _modes() -> list:
    works, why = bwrap_works()
    return [pytest.param(BWRAP, marks=[pytest.mark.sandbox, pytest.mark.skipif(not works, reason=why)]),
            SUBPROCESS]


@pytest.fixture(params=_modes())
def mode(request) -> str:
    """Both isolation modes: for attacks whose outcome depends on the isolation."""
    return request.param


@pytest.fixture
def one_mode(request) -> str:
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


def attack(session: StudentSession, fn: str = "attack", timeout: float | None = None, **args):
    """Run the attack function of the submission through the test probe."""
    return session.call("probe", timeout=timeout, name="attack", args={"fn": fn, **args})


def honest_probe(session: StudentSession):
    return session.call("probe", name="uni_to_diff", args={"v": 0.1, "w": 0.5})
