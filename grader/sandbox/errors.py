"""What a call into the student's worker can raise, each with a message a student can act on.

The grader turns these into a failed check (fail closed): no valid answer means no points.
"""

from __future__ import annotations


class SandboxError(Exception):
    """Base class: something about the student's code stopped a call from giving a valid answer."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message


class StudentError(SandboxError):
    """The student's code raised (or returned something that cannot be sent back).

    `file` and `line` point inside the submission when the failure happened there; `frames` is the
    traceback through the submission's files ({"file", "line", "function", "code"}, innermost last).
    """

    def __init__(self, message: str, type_name: str = "Exception", file: str | None = None,
                 line: int | None = None, frames: list[dict] | None = None) -> None:
        super().__init__(message)
        self.type_name = type_name
        self.file = file
        self.line = line
        self.frames = list(frames or [])

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}: " if self.line else ""
        where = where or (f"{self.file}: " if self.file else "")
        return f"{where}{self.type_name}: {self.message}" if self.type_name else f"{where}{self.message}"


class StudentTimeout(SandboxError):
    """The call did not answer in time (infinite loop, sleep, or the submission's time budget ran out).

    `file`, `line` and `function` say where the student's code was still running when the call was stopped
    (None when unknown: the code was in the grader's own code, or it silenced the stack dump).
    """

    def __init__(self, message: str, file: str | None = None, line: int | None = None,
                 function: str | None = None) -> None:
        super().__init__(message)
        self.file = file
        self.line = line
        self.function = function


class MachineStalled(SandboxError):
    """A wait for the worker passed its wall bound while the worker's own time (CPU and sleep) stayed under
    its limit: the machine held it up (stopped, starved of CPU), not the student's code. Never a verdict
    against the student: the grading redoes the check, and says "graded under load: regrade" if it cannot
    (grader.grading)."""


class WorkerDied(SandboxError):
    """The worker process ended or broke the protocol (exit, os._exit, crash, memory, output abuse)."""


class SandboxUnavailable(Exception):
    """The requested isolation (e.g. bubblewrap) cannot run on this machine. Not a student problem."""
