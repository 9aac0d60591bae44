"""Issue 23: `simiam run` and `simiam migrate` in an emulated Windows (tests/windows_like.py: no POSIX-only
piece in the process). An endless loop in `simiam run` is stopped there too, by the step limit's watchdog
thread (no SIGALRM), with the message and location it gets on Linux."""

from __future__ import annotations

import shutil
from pathlib import Path

import mistakes
from test_migrate import MINE, fill
from windows_like import SIMIAM, WindowsLike

ROOT = Path(__file__).resolve().parents[2]


def test_simiam_run_runs_the_week3_solution_from_a_folder_named_in_another_case(tmp_path: Path) -> None:
    """Inside `Week3` (as a Windows user may have named it), `simiam run week3` takes the current folder."""
    folder = tmp_path / "Week3"
    shutil.copytree(ROOT / "solutions" / "week3", folder)
    done = WindowsLike(tmp_path).run(SIMIAM, "run", "week3", "--seconds", "3", cwd=folder)
    assert done.returncode == 0, done.stderr + done.stdout
    assert (folder / "runs" / "week3.json").is_file() and (folder / "runs" / "week3.html").is_file()


def test_an_endless_loop_in_simiam_run_is_stopped_without_sigalrm(tmp_path: Path) -> None:
    folder = mistakes.build("stuck", "week3_endless_loop", tmp_path, 3, "week3")
    lines = (folder / "go_to_goal.py").read_text().splitlines()
    line = next(i for i, text in enumerate(lines, 1) if "# STUCK" in text)
    # without a step limit the run never ends: 120 s (a 2 s limit, on a loaded machine) says so sooner
    done = WindowsLike(tmp_path).run(SIMIAM, "run", "week3", "--seconds", "3", timeout=120)
    assert done.returncode == 1, done.stderr + done.stdout
    assert "your code did not answer in time: no answer within 2 s, the time limit per step" in done.stderr
    assert (f"it was still running at go_to_goal.py:{line} in GoToGoal.execute "
            "(an endless loop or a long wait?)") in done.stderr


def test_simiam_migrate_carries_week3_into_week4(tmp_path: Path) -> None:
    shutil.copytree(ROOT / "assignments" / "week3", tmp_path / "week3")
    shutil.copytree(ROOT / "assignments" / "week4", tmp_path / "week4")
    fill(tmp_path / "week3", 3)  # the solution's blocks with a line of the student's own
    done = WindowsLike(tmp_path).run(SIMIAM, "migrate", "week4", "--from", "week3")
    assert done.returncode == 0, done.stderr + done.stdout
    assert done.stdout.count("  moved  ") == 4 and "Wrote go_to_goal.py." in done.stdout
    assert (tmp_path / "week4" / "go_to_goal.py").read_text().count(MINE.strip()) == 4


def test_the_watchdog_stops_a_loop_and_never_fires_once_the_step_has_ended(monkeypatch) -> None:
    """The step limit without SIGALRM (run_limit._watchdog), in this process: a loop is stopped, and a
    step that ends just before its limit never gets a StepTimeout later, outside the step (a race the
    lock and the clearing of a pending exception close)."""
    import signal
    import time

    import pytest

    from simiam.run_limit import StepTimeout, step_limit

    monkeypatch.delattr(signal, "setitimer")
    with pytest.raises(StepTimeout), step_limit(0.05):
        while True:
            pass
    leaked = 0
    for _ in range(200):  # steps that end around their limit: the watchdog fires at about that moment
        try:
            with step_limit(0.002):
                end = time.perf_counter() + 0.002
                while time.perf_counter() < end:
                    pass
        except StepTimeout:
            pass  # raised inside the step: what a limit does
        try:
            for _ in range(20000):  # bytecodes outside any step: a StepTimeout here would be a leak
                pass
        except StepTimeout:
            leaked += 1
    assert leaked == 0
