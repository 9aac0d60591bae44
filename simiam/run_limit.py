"""A wall-clock limit on one step of the student's code in `simiam run` (in this process, main thread).

SIGALRM raises StepTimeout inside whatever the student's code is doing, so an endless loop stops with a
traceback; the alarm repeats every half second until the step ends, in case their code catches the first
one. `stuck_at` reads from that traceback where in their files the code was running, in the words `grade`
uses ("go_to_goal.py:52 in GoToGoal.execute").
"""

from __future__ import annotations

import os
import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from simiam.brain import Brain, Readings


class StepTimeout(BaseException):
    """A step of the student's code ran past its limit (a BaseException: `except Exception` in student
    code cannot swallow it)."""


def _raise(_signum, _frame) -> None:
    raise StepTimeout()


@contextmanager
def step_limit(seconds: float) -> Iterator[None]:
    """Raise StepTimeout in the body once it has run `seconds` (no limit off the main thread). Where the
    system has no SIGALRM (Windows) a watchdog thread raises it instead (`_watchdog`)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    if not hasattr(signal, "setitimer"):
        with _watchdog(seconds):
            yield
        return
    previous = signal.signal(signal.SIGALRM, _raise)
    signal.setitimer(signal.ITIMER_REAL, seconds, 0.5)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0, 0)
        signal.signal(signal.SIGALRM, previous)


@contextmanager
def _watchdog(seconds: float) -> Iterator[None]:
    """StepTimeout raised in this thread by another once the body has run `seconds`, then every half
    second until it ends (as the alarm repeats). CPython's PyThreadState_SetAsyncExc delivers it at the
    next bytecode: an endless Python loop stops; a long sleep stops when it returns."""
    import ctypes

    target = ctypes.c_ulong(threading.get_ident())
    lock = threading.Lock()
    done = threading.Event()

    def fire() -> None:
        wait = seconds
        while not done.wait(wait):
            with lock:  # never after the body has ended: the end sets `done` under this lock
                if not done.is_set():
                    ctypes.pythonapi.PyThreadState_SetAsyncExc(target, ctypes.py_object(StepTimeout))
            wait = 0.5

    watcher = threading.Thread(target=fire, name="simiam-step-limit", daemon=True)
    watcher.start()
    try:
        yield
    finally:
        while True:  # the StepTimeout may land here too: retry until the watchdog is off and nothing waits
            try:
                with lock:
                    done.set()
                    ctypes.pythonapi.PyThreadState_SetAsyncExc(target, None)  # drop one not yet raised
                break
            except StepTimeout:
                continue


class LimitedBrain:
    """A Brain whose every step runs under `step_limit(seconds)`: the student's code, not the physics."""

    def __init__(self, brain: Brain, seconds: float) -> None:
        self.brain = brain
        self.seconds = seconds

    def step(self, readings: Readings) -> Any:
        with step_limit(self.seconds):
            return self.brain.step(readings)


def stuck_at(exc: BaseException, folder: Path) -> str | None:
    """`file.py:line in Class.method` of the innermost frame of the traceback inside `folder`, or None."""
    folder = Path(folder).resolve()
    where = None
    tb = exc.__traceback__
    while tb is not None:
        path = Path(os.path.abspath(tb.tb_frame.f_code.co_filename))
        if path.parent == folder:
            code = tb.tb_frame.f_code
            name = getattr(code, "co_qualname", code.co_name)
            place = "at module level" if name == "<module>" else f"in {name}"
            where = f"{path.name}:{tb.tb_lineno} {place}"
        tb = tb.tb_next
    return where
