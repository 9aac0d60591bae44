"""Capture of the student's stdout and stderr: the first bytes are kept for feedback, the rest is counted.

The worker writes to a pipe that a daemon thread drains as fast as it can, so printing 100 MB neither
blocks the worker on a full pipe nor fills the grader's memory or disk. Nothing read here is ever parsed:
a "100/100" or a fake result JSON printed by student code is only shown back to the student, truncated.
"""

from __future__ import annotations

import os
import select
import struct
import threading
import time

from grader.inside.shorten import keep_ends


class CappedOutput:
    """Drains `fd` in a thread; keeps the first `cap` bytes."""

    def __init__(self, fd: int, cap: int) -> None:
        self.cap = cap
        self.total = 0
        self._kept = bytearray()
        self._lock = threading.Lock()
        self._fd = fd
        self._eof = False
        self._thread = threading.Thread(target=self._drain, name="sandbox-output", daemon=True)
        self._thread.start()

    def _drain(self) -> None:
        # poll(), not select(): no FD_SETSIZE limit in a busy batch grader. Where there is no poll()
        # (Windows) the read blocks outside the lock; settle() cannot count the bytes in a pipe there
        # anyway (no fcntl: the "local check only" note says printed output may be cut short).
        poller = select.poll() if hasattr(select, "poll") else None
        if poller is not None:
            poller.register(self._fd, select.POLLIN)
        try:
            while True:
                data = None
                if poller is None:
                    data = os.read(self._fd, 1 << 16)
                else:
                    poller.poll()
                with self._lock:  # held from read to append, so settle() sees every byte accounted
                    if data is None:
                        data = os.read(self._fd, 1 << 16)
                    if not data:
                        self._eof = True
                        break
                    room = self.cap - len(self._kept)
                    if room > 0:
                        self._kept += data[:room]
                    self.total += len(data)
        except OSError:
            self._eof = True
        finally:
            os.close(self._fd)

    def settle(self, timeout: float = 0.5) -> None:
        """Wait until everything already written to the pipe has been read (the worker flushes its
        streams before answering, so after an answer this makes its output complete)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            with self._lock:
                if self._eof or _pending(self._fd) == 0:
                    return
            time.sleep(0.001)

    def join(self, timeout: float = 1.0) -> None:
        """Wait for the writer side to close (all worker processes gone)."""
        self._thread.join(timeout)

    @property
    def dropped(self) -> int:
        with self._lock:
            return self.total - len(self._kept)

    def text(self) -> str:
        """What the student printed, truncated, with a note of how much was dropped."""
        with self._lock:
            kept, dropped = bytes(self._kept), self.total - len(self._kept)
        return _described(kept, dropped)

    def take(self) -> str:
        """`text()`, and start afresh: what is read from now on is kept in a new `cap` bytes, apart from
        what this returned (the grader splits output printed during visible and hidden checks so)."""
        with self._lock:
            kept, dropped = bytes(self._kept), self.total - len(self._kept)
            self._kept.clear()
            self.total = 0
        return _described(kept, dropped)


def _described(kept: bytes, dropped: int) -> str:
    text = kept.decode("utf-8", errors="replace")
    if dropped:
        text += f"\n[... {dropped} more bytes of output not kept]"
    return text


def _pending(fd: int) -> int:
    """Bytes waiting in the pipe (FIONREAD); 0 where fcntl is missing (the result says so)."""
    try:
        import fcntl
        import termios

        return struct.unpack("i", fcntl.ioctl(fd, termios.FIONREAD, b"\0\0\0\0"))[0]
    except (OSError, ImportError):
        return 0


def cut_middle(text: str, limit: int) -> str:
    """What the student printed in at most `limit` characters: the first and the last whole lines, the
    middle replaced by a note of how much was cut (grader.inside.shorten). The first lines say what the code
    printed first (where a student looks for their debug output), the last ones what it printed just
    before it stopped."""
    return keep_ends(text, limit, whole_lines=True)
