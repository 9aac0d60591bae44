"""Issue 23: `grade` on a system with none of the POSIX-only pieces (Windows), emulated on Linux.

No Windows machine is available, so the grading process and every worker run under
tests/data/windows_like/no_posix.py, which removes what Windows lacks before anything is imported: fcntl,
resource, termios, pwd; select.poll/epoll; os.fork, setsid, killpg, uids; the signals Windows lacks; /proc
(for Python code); seccomp. PATH holds no bubblewrap, only an emulated `taskkill` (tests/data/windows_like/
taskkill) that logs each call. The week-3 solution then scores full marks and the stub 0 through the
portable channel (grader.sandbox.channel); an endless loop times out, and a child process started by the
submission is gone when `grade` returns, killed by the `taskkill /T` path.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from mistakes import build
from windows_like import DATA, GRADE, SHIM, WindowsLike

import grader

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def emulated(tmp_path: Path) -> WindowsLike:
    return WindowsLike(tmp_path)


@pytest.fixture
def windows_like(emulated: WindowsLike, tmp_path: Path):
    """grade(week, folder, *args) -> (CompletedProcess, result JSON or None) in the emulated Windows."""

    def grade(week: str, folder: Path, *args: str) -> tuple[subprocess.CompletedProcess, dict | None]:
        report = tmp_path / f"out-{folder.name}" / "result.json"
        done = emulated.run(GRADE, week, str(folder), "--out", str(report.parent), "--json", str(report),
                            *args)
        return done, json.loads(report.read_text()) if report.exists() else None

    return grade


def test_the_emulation_really_removes_the_posix_pieces() -> None:
    """The emulation is what the other tests rest on: check it removes what it claims, in a worker too."""
    script = DATA / "what_is_left.py"
    env = {"PATH": "/usr/bin:/bin", "PYTHONPATH": str(Path(grader.__file__).resolve().parents[1])}
    done = subprocess.run([sys.executable, str(SHIM), "worker", "-I", str(script)], capture_output=True,
                          text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split("\n")[0] == "[] [] gone False"


def test_the_solution_scores_full_marks_through_the_portable_channel(windows_like) -> None:
    done, result = windows_like("week3", REPO / "solutions" / "week3")
    assert done.returncode == 0, done.stderr + done.stdout
    assert result is not None and result["status"] == "graded"
    assert result["score"] == result["max_score"] > 0
    assert result["isolation"] == "subprocess"
    note = result["isolation_note"]
    assert note.startswith("local check only: ")
    assert "resource module is missing" in note and "no seccomp" in note and "fcntl" in note
    assert "local check only:" in done.stdout


def test_the_stub_scores_zero_there(windows_like) -> None:
    done, result = windows_like("week3", REPO / "assignments" / "week3")
    assert done.returncode == 1, done.stderr + done.stdout
    assert result is not None and result["score"] == 0 < result["max_score"]
    assert "local check only:" in done.stdout


def test_an_endless_loop_times_out_and_its_worker_is_killed(windows_like, emulated, tmp_path: Path) -> None:
    folder = build("stuck", "week3_endless_loop", tmp_path / "subs")
    done, result = windows_like("week3", folder, "--check", "week3.go_to_goal.reach_goals")
    assert done.returncode == 1, done.stderr + done.stdout
    assert result is not None and result["score"] == 0
    text = json.dumps(result)
    assert "time limit per call" in text
    # the timed-out worker was ended through taskkill /T (no process groups here)
    assert emulated.killed()


def test_a_child_process_of_the_submission_is_gone_when_grade_returns(windows_like, emulated,
                                                                      tmp_path: Path) -> None:
    folder = build("windows_like", "child_process", tmp_path / "subs")
    pid_file = tmp_path / "child.pid"
    source = folder / "go_to_goal.py"
    source.write_text(source.read_text().replace("CHILD_PID_FILE", str(pid_file)))
    done, result = windows_like("week3", folder, "--check", "week3.pid.proportional")
    assert result is not None, done.stderr + done.stdout
    children = [int(line) for line in pid_file.read_text().split()]
    try:
        assert children  # the submission did start its child processes
        assert set(children) <= emulated.killed()  # taskkill /T reached them through the worker's tree
        for pid in children:
            assert not _alive(pid), f"the submission's child {pid} outlived grade"
    finally:  # a wrong version leaves them: do not leave them sleeping on the machine
        for pid in children:
            if _alive(pid):
                os.kill(pid, 9)


def _alive(pid: int) -> bool:
    """True if `pid` runs (a zombie waiting for a parent that does not reap is not running)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:
        state = Path(f"/proc/{pid}/stat").read_bytes().rsplit(b")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state not in (b"Z", b"X")


def test_the_worker_environment_keeps_only_what_windows_needs_to_start_python(monkeypatch) -> None:
    """On Windows Python does not start without SYSTEMROOT; the rest of the grader's environment (tokens,
    paths) still stays out of the worker's."""
    from grader.sandbox import isolation

    monkeypatch.setenv("SYSTEMROOT", "C:\\Windows")
    monkeypatch.setenv("TEMP", "C:\\Users\\ana\\AppData\\Local\\Temp")
    monkeypatch.setenv("GITHUB_TOKEN", "secret")
    linux = isolation.clean_env()
    monkeypatch.setattr(os, "name", "nt")
    windows = isolation.clean_env()
    monkeypatch.undo()
    assert "SYSTEMROOT" not in linux and "GITHUB_TOKEN" not in linux
    assert windows["SYSTEMROOT"] == "C:\\Windows" and windows["TEMP"].endswith("Temp")
    assert "GITHUB_TOKEN" not in windows and set(windows) - set(linux) <= set(isolation.WINDOWS_ENV)


def test_the_request_writer_thread_never_blocks_the_grader() -> None:
    """Windows' path (grader.sandbox.channel._Writer): a request the worker does not read gives up after
    its time instead of blocking the grader; one to a worker that is gone fails at once."""
    from grader.sandbox.channel import _Writer

    read_end, write_end = os.pipe()
    writer = _Writer(write_end)
    assert writer.write(b"ping\n", 5.0)  # fits in the pipe: done
    assert not writer.write(b"x" * (4 << 20), 0.2)  # nobody reads 4 MB: given up, the grader goes on
    os.close(read_end)  # the worker is gone: the blocked write fails, and so does every later one
    assert not writer.write(b"ping\n", 5.0)
    writer.stop()


def test_batch_grading_says_it_needs_linux_or_macos(emulated: WindowsLike, tmp_path: Path) -> None:
    """The class-wide batch locks files with fcntl and passes descriptors to its grading processes: on
    Windows it stops with a sentence, not an ImportError traceback, and grading one submission still works."""
    (tmp_path / "class").mkdir()
    done = emulated.run(GRADE, "week3", "--batch", str(tmp_path / "class"))
    assert done.returncode == 2, done.stderr + done.stdout
    assert done.stderr.startswith("grade: --batch (grading a whole class) needs Linux or macOS")
    assert "Traceback" not in done.stderr


def test_the_job_object_structure_has_windows_layout_and_is_not_made_elsewhere() -> None:
    """grader.sandbox.winjob cannot run here; what can be checked is its structure's size (144 bytes for
    JOBOBJECT_EXTENDED_LIMIT_INFORMATION on 64-bit Windows: a wrong field type shifts LimitFlags and the
    kill-on-close flag lands elsewhere) and that no job is attempted off Windows (taskkill is used)."""
    import ctypes

    from grader.sandbox.winjob import ExtendedLimits, contain

    if ctypes.sizeof(ctypes.c_void_p) == 8:
        assert ctypes.sizeof(ExtendedLimits) == 144
        assert ExtendedLimits.BasicLimitInformation.offset == 0
        assert ExtendedLimits.IoInfo.offset == 64
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    try:
        assert contain(process) is None
    finally:
        process.wait()


def test_what_the_student_prints_comes_back_there(windows_like, tmp_path: Path) -> None:
    """Printed output goes through fd 1 -> fd 2 in the worker and the output thread's blocking reads here
    (no poll(), no FIONREAD): the first debug line is in the result, and the check still passes."""
    folder = build("submissions", "week2_debug_prints", tmp_path / "subs")
    done, result = windows_like("week2", folder, "--check", "week2.go_to_angle.reaches_theta_d")
    assert result is not None, done.stderr + done.stdout
    assert result["checks"][0]["status"] == "passed"
    assert result["student_output"].startswith("debug call 1: v = ")
