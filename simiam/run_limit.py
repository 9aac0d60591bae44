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
    next bytecode: an endless Python loop stops; a long sleep stops when it returns.

    The exception may land anywhere in this thread, even in this function's own lines: `ended` (a plain
    flag, set in one bytecode) is read and written only under `lock`, and a pending exception is dropped
    under it, so once the `with lock` in `finally` has run, none can come."""
    import ctypes

    target = ctypes.c_ulong(threading.get_ident())
    lock = threading.Lock()
    ended = [False]
    wake = threading.Event()  # only to end the watcher early; the decision is `ended`

    def fire() -> None:
        wait = seconds
        while not wake.wait(wait):
            with lock:
                if ended[0]:
                    return
                ctypes.pythonapi.PyThreadState_SetAsyncExc(target, ctypes.py_object(StepTimeout))
            wait = 0.5

    watcher = threading.Thread(target=fire, name="simiam-step-limit", daemon=True)
    try:
        watcher.start()
        yield
    finally:
        while True:
            try:
                with lock:
                    ended[0] = True
                    ctypes.pythonapi.PyThreadState_SetAsyncExc(target, None)  # drop one not yet raised
                break
            except StepTimeout:  # it landed here, before the flag was set: set it again
                continue
        wake.set()


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
