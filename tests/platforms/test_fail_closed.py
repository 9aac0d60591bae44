"""Issue 30 item 4: official grading fails closed where student code would run under the grader's own uid
with no sandbox (Coursera's non-root containers when they forbid namespaces, any platform like them), and
the platforms' entrypoints trust no feedback file after a grader that did not finish.

The attack (tests/data/attacks/graded/coursera_forge.patch) writes a full-marks /shared/feedback.json and a
mark that it ran, then kills its grader; before, Coursera's entrypoint kept any non-empty feedback.json, so
the forgery stood. The grader is the real one, run through the real entrypoint script; what cannot be made
here without a container (a grader that is not root and a bubblewrap that cannot create namespaces) is
emulated in the grading process (capabilities.is_root and isolation.bwrap_works answer as they would there).
tests/platforms/test_coursera.py runs the same refusal in a container-like namespace as uid 1000.
"""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
from mistakes import ROOT, build

from grader.platforms.bundle import build_config, course_hidden_file
from grader.platforms.official import NoSandbox, grade_upload, read_secret, refuse_unsandboxed, write_secret
from grader.sandbox import capabilities, isolation

SEED = 918273645
WHY = "bubblewrap cannot create a sandbox here: bwrap: No permissions to create new namespace"
TEMPLATES = ROOT / "grader" / "platforms" / "templates"
# the grading process as Coursera runs it where namespaces are forbidden: not root, bubblewrap refused
EMULATE = (f"import sys; sys.path.insert(0, {str(ROOT)!r}); "
           "from grader.sandbox import capabilities, isolation; "
           "capabilities.is_root = lambda: False; "
           f"isolation.bwrap_works = lambda: (False, {WHY!r}); "
           "from grader.platforms.coursera import main; sys.exit(main(sys.argv[1:]))")


@pytest.fixture
def folder():
    """A folder every uid can reach (the worker's too), removed afterwards."""
    base = Path(tempfile.mkdtemp(prefix="simiam-fail-closed-"))
    base.chmod(0o755)
    yield base
    subprocess.run(["chmod", "-R", "u+rwX", str(base)], check=False)
    subprocess.run(["rm", "-rf", str(base)], check=False)


@pytest.mark.parametrize("bwrap, root, spare_uid, refused", [
    (True, False, False, False), (False, True, True, False), (True, True, True, False),
    (False, False, False, True), (False, True, False, True)])   # the last: root with no uid to drop to
def test_official_grading_refuses_only_where_nothing_keeps_student_code_from_the_grader(
        monkeypatch, bwrap, root, spare_uid, refused):
    monkeypatch.setattr(isolation, "bwrap_works", lambda: (bwrap, "" if bwrap else WHY))
    monkeypatch.setattr(capabilities, "is_root", lambda: root)
    monkeypatch.setattr(isolation, "pick_uid", lambda: 234_567 if spare_uid else None)
    if not refused:
        refuse_unsandboxed()
        return
    with pytest.raises(NoSandbox) as exc:
        refuse_unsandboxed()
    said = str(exc.value)
    assert WHY in said and "grader's own uid" in said and "Nothing was graded" in said
    assert "user namespaces" in said and "as root" in said and "docs/platforms.md" in said


def test_grade_upload_refuses_before_any_student_code_runs(monkeypatch, folder):
    monkeypatch.setattr(isolation, "bwrap_works", lambda: (False, WHY))
    monkeypatch.setattr(capabilities, "is_root", lambda: False)
    monkeypatch.delenv("SIMIAM_HIDDEN", raising=False)
    attack = _attack(folder)
    secret = write_secret(folder / "secret", 3, SEED, None)
    with pytest.raises(NoSandbox):
        grade_upload(attack, read_secret(secret))
    assert not (folder / "shared" / "ran.txt").exists(), "student code ran"
    assert "SIMIAM_HIDDEN" not in os.environ


def _attack(folder: Path) -> Path:
    shared = folder / "shared"
    (shared / "submission").mkdir(parents=True)
    shared.chmod(0o777)                    # the grader's own uid could write here: any uid may in the test
    attack = build("attacks/graded", "coursera_forge", folder)
    code = (attack / "go_to_goal.py").read_text().replace("__SHARED__", str(shared))
    (attack / "go_to_goal.py").write_text(code)
    return attack


def _coursera_home(folder: Path) -> Path:
    from grader.platforms.handout import copy_handout

    home = folder / "home"
    secret = write_secret(home / "secret", 3, SEED, course_hidden_file(ROOT, 3))
    config = {**build_config(3, "hidden", secret / "hidden"), "coursera_part_id": None}
    (home / "config.json").write_text(json.dumps(config), encoding="utf-8")
    copy_handout(3, ROOT, home / "handout")
    return home


def _fake_venv(folder: Path, script: str) -> Path:
    """A venv whose bin/python is `script` (sh), as the entrypoints call it."""
    venv = folder / "venv"
    (venv / "bin").mkdir(parents=True)
    python = venv / "bin" / "python"
    python.write_text("#!/bin/sh\n" + script)
    python.chmod(0o755)
    return venv


def test_coursera_refuses_and_the_forgery_never_happens(folder):
    attack = _attack(folder)
    shared = folder / "shared"
    for path in attack.glob("*.py"):
        (shared / "submission" / path.name).write_bytes(path.read_bytes())
    home = _coursera_home(folder)
    # the entrypoint's python: the real grader, in a process that sees what Coursera's container shows
    venv = _fake_venv(folder, f'shift 3; exec {sys.executable} -c "$EMULATE" "$@"\n')  # drop "-I -m X"
    env = {"PATH": "/usr/bin:/bin", "COURSERA_SHARED": str(shared), "SIMIAM_HOME": str(home),
           "SIMIAM_VENV": str(venv), "EMULATE": EMULATE, "HOME": str(folder)}
    done = subprocess.run(["sh", str(TEMPLATES / "coursera_entrypoint.sh")], env=env, capture_output=True,
                          text=True, timeout=600)
    feedback = json.loads((shared / "feedback.json").read_text())
    assert not (shared / "ran.txt").exists(), "student code ran under the grader's own uid"
    assert feedback["fractionalScore"] == 0.0 and "forged" not in feedback["feedback"], feedback
    assert "not set up to run code safely" in feedback["feedback"]
    assert "official grading refused" in done.stderr and "user namespaces" in done.stderr   # for the staff
    assert done.returncode == 0 and done.stdout == ""


# ---- the entrypoints trust no feedback after a grader that did not finish --------------------------------
FORGE = {"coursera": ('{"fractionalScore": 1.0, "feedback": "forged"}', "feedback.json"),
         "gradescope": ('{"score": 100.0, "tests": []}', "results/results.json"),
         "prairielearn": ('{"gradable": true, "score": 1.0}', "results/results.json")}


def _entrypoint(platform: str, folder: Path, then: str) -> tuple[subprocess.CompletedProcess, Path]:
    """Run `platform`'s entrypoint with a grader that forges its feedback file, then does `then`
    (`kill`: dies by SIGKILL; `lock`: makes the folder read-only and fails)."""
    text, name = FORGE[platform]
    root = folder / "root"
    (root / "results").mkdir(parents=True)
    target = root / name
    lock = f'chmod 0555 "{target.parent}"; exit 1' if then == "lock" else "kill -9 $$"
    venv = _fake_venv(folder, f"printf '%s\\n' '{text}' > \"{target}\"\n{lock}\n")
    for path in (folder, root, root / "results"):
        path.chmod(0o777)
    if os.geteuid() == 0:   # the feedback folder is the grader's own, as /shared is on Coursera
        for path in (root, root / "results"):
            os.chown(path, 65534, 65534)
    script = {"coursera": "coursera_entrypoint.sh", "gradescope": "gradescope_run_autograder",
              "prairielearn": "prairielearn_entrypoint.sh"}[platform]
    env = {"PATH": "/usr/bin:/bin", "COURSERA_SHARED": str(root), "AUTOGRADER_ROOT": str(root),
           "GRADE_ROOT": str(root), "SIMIAM_HOME": str(root), "SIMIAM_VENV": str(venv)}
    nobody = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"] if os.geteuid() == 0 else []
    shell = "bash" if platform == "gradescope" else "sh"
    copy = folder / script                     # where the unprivileged uid can read it
    copy.write_bytes((TEMPLATES / script).read_bytes())
    copy.chmod(0o755)
    done = subprocess.run([*nobody, shell, str(copy), str(root / "secret")], env=env, capture_output=True,
                          text=True, timeout=60)
    return done, target


@pytest.mark.parametrize("platform", sorted(FORGE))
def test_a_killed_grader_leaves_no_forged_feedback(folder, platform):
    done, target = _entrypoint(platform, folder, "kill")
    said = target.read_text()
    assert "forged" not in said and "100.0" not in said and '"gradable": true' not in said, said
    assert "failed" in said, said
    assert done.returncode == 0, done.stderr


@pytest.mark.parametrize("platform", sorted(FORGE))
def test_a_folder_made_read_only_fails_the_grading_rather_than_keep_a_forgery(folder, platform):
    if os.geteuid() == 0 and not Path("/usr/bin/setpriv").exists():
        pytest.skip("needs setpriv to run the entrypoint as an unprivileged user, as Coursera does")
    done, target = _entrypoint(platform, folder, "lock")
    said = target.read_text()
    forged = "forged" in said or "100.0" in said or '"gradable": true' in said
    # the forgery could not be replaced: the entrypoint says the grading failed (a non-zero exit)
    assert not forged or done.returncode != 0, (done.returncode, said, done.stderr)
    assert stat.S_IMODE(target.parent.stat().st_mode) == 0o555
