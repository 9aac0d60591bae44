"""Issue 11: `grade` starts where `resource`, `fcntl` or bubblewrap are missing (macOS, a Linux without user
namespaces), runs student code in a plain subprocess with the limits the system offers, and every result
says so ("local check only: ..."). Tested on Linux by blocking those modules and hiding bwrap."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import grader
from grader.sandbox.exposed import EXPOSED

REPO = Path(__file__).resolve().parents[2]

# The grading process of a system without resource/fcntl (blocked in sys.modules before any import) and
# without bubblewrap (PATH holds no bwrap); then the ordinary command line.
GRADE = """
import sys
sys.modules.update(resource=None, fcntl=None, termios=None)
from grader.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _grade(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    env = {"PATH": str(tmp_path / "no-bin"), "HOME": str(tmp_path), "LANG": "C.UTF-8",
           "PYTHONPATH": str(Path(grader.__file__).resolve().parents[1])}
    return subprocess.run([sys.executable, "-c", GRADE, *args], capture_output=True, text=True, env=env,
                          cwd=tmp_path, timeout=300)


def test_grade_runs_without_resource_fcntl_and_bubblewrap_and_says_so(tmp_path: Path) -> None:
    out = tmp_path / "out"
    done = _grade(tmp_path, "week2", str(REPO / "solutions" / "week2"), "--out", str(out))
    assert done.returncode == 0, done.stderr + done.stdout
    result = json.loads((out / "week2.json").read_text())
    assert result["status"] == "graded" and result["score"] == result["max_score"] > 0
    assert result["isolation"] == "subprocess"
    note = result["isolation_note"]
    assert note.startswith("local check only: ")
    assert "no bubblewrap sandbox" in note and "resource module is missing" in note and "fcntl" in note
    assert "local check only:" in done.stdout  # the terminal says it too
    assert "local check only:" in (out / "week2.html").read_text()


def test_a_stub_still_scores_zero_there(tmp_path: Path) -> None:
    """The same degraded system still grades honestly: the week-2 stub earns nothing on the coded parts."""
    out = tmp_path / "out"
    done = _grade(tmp_path, "week2", str(REPO / "assignments" / "week2"), "--out", str(out),
                  "--check", "week2.uni_to_diff.round_trip")
    assert done.returncode == 1, done.stderr + done.stdout
    assert "FAIL" in done.stdout and "local check only:" in done.stdout


WORKER_SIDE = """
import sys
sys.modules.update(resource=None, fcntl=None, termios=None)
sys.path[:0] = {paths!r}
import importlib
for name in {modules!r}:
    importlib.import_module(name)
from grader.inside.rlimits import apply_rlimits
print(apply_rlimits({{"cpu": 5, "memory": 1 << 30, "file": 1 << 20, "open_files": 64, "processes": 8}}))
"""


def test_the_worker_side_imports_without_resource_or_fcntl() -> None:
    modules = [f.removesuffix(".py").removesuffix("/__init__").replace("/", ".") for f in EXPOSED]
    code = WORKER_SIDE.format(paths=[str(Path(grader.__file__).resolve().parents[1])], modules=modules)
    done = subprocess.run([sys.executable, "-I", "-c", code], capture_output=True, text=True, timeout=60,
                          env={"PATH": os.environ.get("PATH", "")})
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "None"  # nothing to set, and it says so


REFUSING = """
import sys
sys.path[:0] = {paths!r}
import resource
real = resource.setrlimit

def refuse_memory(which, limits):  # what a system that does not support RLIMIT_AS does
    if which == resource.RLIMIT_AS:
        raise ValueError("not allowed to raise maximum limit")
    real(which, limits)

resource.setrlimit = refuse_memory
from grader.inside.rlimits import apply_rlimits
print(apply_rlimits({{"cpu": 5, "memory": 1 << 30, "file": 1 << 20, "open_files": 64, "processes": 64}}))
print(resource.getrlimit(resource.RLIMIT_FSIZE)[0])
"""


def test_a_limit_the_system_refuses_is_named_and_the_others_still_apply() -> None:
    """macOS may refuse RLIMIT_AS: the worker still starts, with every other limit, and says which."""
    code = REFUSING.format(paths=[str(Path(grader.__file__).resolve().parents[1])])
    done = subprocess.run([sys.executable, "-I", "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["['memory']", str(1 << 20)]


def test_refused_limits_lead_the_note() -> None:
    from grader.sandbox.capabilities import with_refused_limits

    assert with_refused_limits("bubblewrap sandbox: ...", ["memory", "<script>"]) == (
        "local check only: this system refused these kernel limits: memory. bubblewrap sandbox: ...")
    assert with_refused_limits("local check only: no seccomp. X", ["processes"]).startswith(
        "local check only: this system refused these kernel limits: processes. no seccomp. X")
    assert with_refused_limits("note", "memory") == "note"  # not a list: ignored
