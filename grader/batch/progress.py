"""The batch progress line on stderr: done/total, running counts by status, rate and ETA.

On a terminal it is one line rewritten in place (at most ten times a second); in a log file or CI it is
a plain line every ``period_s`` seconds and at the end, so logs stay readable. ``quiet`` prints nothing.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from typing import TextIO

from grader.inside.shorten import keep_head
from grader.untrusted import printable

COUNTED = ("graded", "invalid", "held", "timeout", "crashed", "skipped")
QUIET_AT_ZERO = ("held", "skipped")     # named only once some student has them
MESSAGE_CHARS = 400  # a student's message in the log: the rest is in their report


def format_duration(seconds: float) -> str:
    """``42s``, ``3m05s``, ``1h02m``."""
    seconds = max(0, int(round(seconds)))
    if seconds < 60:
        return f"{seconds}s"
    if seconds < 3600:
        return f"{seconds // 60}m{seconds % 60:02d}s"
    return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m"


class Progress:
    """Counts finished submissions and shows them. Call :meth:`done` per student, :meth:`close` at the end."""

    def __init__(self, total: int, stream: TextIO | None = None, quiet: bool = False,
                 tty: bool | None = None, period_s: float = 10.0,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.total, self.quiet, self.period_s, self.clock = total, quiet, period_s, clock
        self.stream = stream if stream is not None else sys.stderr
        self.tty = self.stream.isatty() if tty is None else tty
        self.counts = dict.fromkeys(COUNTED, 0)
        self.start = clock()
        self.last_shown = float("-inf")
        self.width = 0

    @property
    def finished(self) -> int:
        return sum(self.counts.values())

    def done(self, status: str) -> None:
        """One more student finished with ``status`` (``skipped`` = reused from an earlier run)."""
        self.counts[status if status in self.counts else "crashed"] += 1
        self._show(final=False)

    def line(self) -> str:
        """The text of the progress line."""
        elapsed = self.clock() - self.start
        worked = self.finished - self.counts["skipped"]
        left = self.total - self.finished
        pct = 100 * self.finished // self.total if self.total else 100
        parts = [f"[{self.finished}/{self.total}] {pct:3d}%"]
        parts.append(" ".join(f"{name} {self.counts[name]}" for name in COUNTED
                              if self.counts[name] or name not in QUIET_AT_ZERO))
        if worked and elapsed > 0:
            rate = worked / elapsed
            parts.append(f"{rate * 60:.1f}/min")
            if left:
                parts.append(f"ETA {format_duration(left / rate)}")
        parts.append(f"elapsed {format_duration(elapsed)}")
        return " | ".join(parts)

    def _show(self, final: bool) -> None:
        if self.quiet:
            return
        now = self.clock()
        if self.tty:
            if final or now - self.last_shown >= 0.1:
                text = self.line()
                self.stream.write("\r" + text.ljust(self.width) + ("\n" if final else ""))
                self.width = len(text)
                self.stream.flush()
                self.last_shown = now
        elif final or (now - self.last_shown >= self.period_s and self.finished < self.total):
            # the last student's line is left to close(), so a log does not end with the same line twice
            self.stream.write(self.line() + "\n")
            self.stream.flush()
            self.last_shown = now

    def close(self) -> None:
        """Show the final line."""
        self._show(final=True)

    def message(self, text: str) -> None:
        """A line of its own (a warning), without garbling the progress line on a terminal. The text is
        untrusted (student ids, messages): it is made printable and kept to one line of bounded length."""
        if self.quiet:
            return
        text = printable(text, multiline=False)
        text = keep_head(text, MESSAGE_CHARS)
        if self.tty and self.width:
            self.stream.write("\r" + " " * self.width + "\r")
            self.width = 0
        self.stream.write(text + "\n")
        self.stream.flush()
