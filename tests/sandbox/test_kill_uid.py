"""kill_uid (the sweep of a dedicated uid's processes, subprocess mode as root) runs its `kill` as that uid:
it must pick one the uid can run, whatever root's PATH holds. The old choice (sandbox_wrong/path_kill.py)
took the first on PATH, and every grading crashed where that was in a folder only root can enter."""

from __future__ import annotations

import os
import shutil
import subprocess
import time
from pathlib import Path

import pytest
from sandbox_wrong import path_kill

from grader.sandbox import reach, runner
from grader.sandbox.isolation import pick_uid


@pytest.fixture
def private_kill_first(tmp_path: Path, monkeypatch) -> Path:
    """PATH starts with a folder only its owner can enter, holding a link to the system's kill."""
    private = tmp_path / "private-bin"
    private.mkdir(mode=0o700)
    real = next(p for p in ("/usr/bin/kill", "/bin/kill") if os.path.exists(p))
    (private / "kill").symlink_to(real)
    monkeypatch.setenv("PATH", f"{private}:{os.environ.get('PATH', '/usr/bin:/bin')}")
    return private / "kill"


def test_the_helper_is_one_the_uid_can_run(private_kill_first: Path) -> None:
    assert not reach.executable(private_kill_first)  # others cannot pass through a 0700 folder
    helper = runner._kill_helper()
    assert reach.executable(helper[0]), helper
    assert not helper[0].startswith(str(private_kill_first.parent)), helper
    wrong = path_kill.kill_helper()[0]
    assert wrong == str(private_kill_first) and not reach.executable(wrong), wrong


@pytest.mark.skipif(os.name != "posix" or os.geteuid() != 0 or pick_uid() is None,
                    reason="kill_uid sweeps a dedicated uid: only as root with spare uids (subprocess mode)")
def test_kill_uid_kills_with_a_private_kill_first_on_path(private_kill_first: Path, monkeypatch) -> None:
    uid = pick_uid()
    assert uid is not None
    sleep = [os.path.realpath(shutil.which("sleep") or "/bin/sleep"), "60"]  # by a path the uid can run
    sleeper = subprocess.Popen(sleep, user=uid, group=uid, extra_groups=[], cwd="/")
    try:
        runner.kill_uid(uid)
        assert sleeper.wait(timeout=10) == -9, "the uid's process survived kill_uid"
        monkeypatch.setattr(runner, "_kill_helper", path_kill.kill_helper)
        with pytest.raises(PermissionError):  # the old choice: the grading itself dies
            again = subprocess.Popen(sleep, user=uid, group=uid, extra_groups=[], cwd="/")
            try:
                runner.kill_uid(uid)
            finally:
                again.kill()
                again.wait()
    finally:
        if sleeper.poll() is None:
            sleeper.kill()
            sleeper.wait()
    deadline = time.monotonic() + 5
    while runner._uid_alive(uid) and time.monotonic() < deadline:
        time.sleep(0.01)
    assert not runner._uid_alive(uid)
