"""Wrong versions of grader.sandbox.worker_clock, each caught by the load tests (tests/sandbox/
test_worker_clock.py, tests/grader/test_under_load.py)."""

from __future__ import annotations

import time

from grader.sandbox.worker_clock import STUDENT, CallClock


class WallClock(CallClock):
    """The limit checker before issue 34: the wall clock since the request decides. A worker the machine
    stopped for 3 s (or starved of CPU) times out against the student."""

    def next_wait(self) -> float:
        return max(0.0, self.began + self.limit - time.monotonic())

    def look(self) -> str | None:
        self.own = self.wall
        return STUDENT if self.wall >= self.limit else None
