"""Issue 22, item 7: a platform's official grading where bubblewrap cannot run (a Docker container with the
default capabilities) says what really ran, never "local check only ... Official grading runs it in the full
sandbox", and still holds student code to a dedicated uid, the seccomp filter and the kernel limits.

Here bubblewrap is made to fail the way it fails there (isolation.bwrap_works, which both the choice of
mode and the note ask); tests/platforms/test_platform_layout.py runs the same upload in a real container-like
mount where bubblewrap cannot create namespaces. The attack (platform_no_sandbox.patch) earns theta_g only if
it got out: root, the secret, a network socket, a new process or a lifted memory limit.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from mistakes import build

from grader.platforms.official import NoSandbox, grade_upload, read_secret, write_secret
from grader.sandbox import isolation
from grader.sandbox.capabilities import LOCAL_ONLY, OFFICIAL_PARTIAL, with_refused_limits

SEED = 918273645
WHY = "bubblewrap cannot create a sandbox here: bwrap: No permissions to create new namespace"


@pytest.fixture
def no_namespaces(monkeypatch):
    monkeypatch.setattr(isolation, "bwrap_works", lambda: (False, WHY))
    monkeypatch.delenv("SIMIAM_HIDDEN", raising=False)   # grade_upload points it at the secret
    monkeypatch.delenv("SIMIAM_HANDOUT", raising=False)


def _official(tmp_path: Path, source: Path) -> dict:
    secret = write_secret(tmp_path / "secret", 3, SEED, None)
    upload = tmp_path / "upload"
    upload.mkdir()
    for path in sorted(source.glob("*.py")):
        shutil.copy(path, upload / path.name)
    try:
        return grade_upload(upload, read_secret(secret))
    finally:
        os.environ.pop("SIMIAM_HIDDEN", None)


def test_official_grading_without_bubblewrap_says_what_ran(tmp_path, no_namespaces):
    attack = build("attacks/graded", "platform_no_sandbox", tmp_path)
    code = (attack / "go_to_goal.py").read_text().replace("__SECRET__", str(tmp_path / "secret"))
    (attack / "go_to_goal.py").write_text(code)
    if os.geteuid() != 0:   # the worker would keep the grader's uid: official grading refuses (issue 30)
        with pytest.raises(NoSandbox, match="grader's own uid"):
            _official(tmp_path, attack)
        return
    result = _official(tmp_path, attack)
    note = result["isolation_note"]
    assert result["isolation"] == "subprocess" and note.startswith(OFFICIAL_PARTIAL + ": ")
    assert LOCAL_ONLY not in note and "Official grading runs it in the full sandbox" not in note
    assert WHY in note and "docs/platforms.md" in note
    checks = {c["id"]: c for c in result["checks"]}
    assert checks["week3.go_to_goal.theta_g"]["status"] == "failed", result["student_output"]
    assert "escaped: []" in result["student_output"]      # it ran, and nothing it tried worked
    assert "under its own unprivileged uid" in note   # what a platform gives: the worker drops to its own uid


def test_refused_limits_keep_the_official_heading():
    note = with_refused_limits(OFFICIAL_PARTIAL + ": this grading machine cannot ...", ["memory", "bogus"])
    assert note.startswith(OFFICIAL_PARTIAL + ": this system refused these kernel limits: memory. ")
    assert LOCAL_ONLY not in note


def test_local_grading_still_says_local_check_only(tmp_path, no_namespaces):
    from grader.grading import grade_submission

    root = Path(__file__).resolve().parents[2]
    result = grade_submission(3, root / "solutions" / "week3", only="week3.go_to_goal.theta_g")
    assert result["isolation_note"].startswith(LOCAL_ONLY + ": ")
