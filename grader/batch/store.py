"""The output folder of a batch: file names, atomic writes, and one writer at a time.

Every file is written to a temporary name in the same folder and moved into place with ``os.replace``,
so a batch killed at any instant leaves each file either complete or absent. A student's HTML is written
before their JSON: the JSON is the commit record the resume logic trusts.
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
from collections.abc import Iterator
from pathlib import Path

# The batch's own files; a student with one of these ids gets a suffixed file name instead.
RESERVED = frozenset({"batch", "summary", "gradebook", "gradescope"})


class OutputBusy(Exception):
    """Another batch is writing to the same output folder."""


def student_stem(student_id: str) -> str:
    """The file name (without suffix) of a student's JSON and HTML in the output folder."""
    return f"{student_id}.student" if student_id.lower() in RESERVED else student_id


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` so that readers see the old file or the new one, never a torn one."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    with open(tmp, "w", encoding="utf-8") as stream:
        stream.write(text)
        stream.flush()
        os.fsync(stream.fileno())
    os.replace(tmp, path)


def write_json(path: Path, value: object) -> None:
    """Atomically write ``value`` as indented, key-sorted JSON (stable bytes for stable results)."""
    write_atomic(path, json.dumps(value, indent=2, sort_keys=True, allow_nan=False) + "\n")


def read_json(path: Path) -> dict | None:
    """A stored result, or None if it is missing or unreadable (then it is simply graded again)."""
    try:
        value = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return value if isinstance(value, dict) else None


@contextlib.contextmanager
def exclusive(out: Path) -> Iterator[None]:
    """Hold ``out/.batch.lock`` for the whole run; a second batch on the same folder is refused."""
    out.mkdir(parents=True, exist_ok=True)
    with open(out / ".batch.lock", "w") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            if exc.errno in (errno.EAGAIN, errno.EWOULDBLOCK, errno.EACCES):
                raise OutputBusy(f"another batch is already writing to {out}") from None
            # a file system without locks (some network mounts): carry on unlocked rather than refuse
        for stale in out.glob(".*.tmp"):   # left by a batch that was killed mid-write
            stale.unlink(missing_ok=True)
        for stale in out.glob("gradescope/*/.*.tmp"):
            stale.unlink(missing_ok=True)
        yield
