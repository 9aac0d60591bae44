"""The output folder of a batch: file names, atomic writes, and one writer at a time.

Every file is written through simiam.safe_write (a random temporary name in the same folder, created
exclusively, moved into place with ``os.replace``; never through a link), so a batch killed at any instant
leaves each file either complete or absent. A student's HTML is written before their JSON: the JSON is the
commit record the resume logic trusts.
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
import secrets
from collections.abc import Iterator
from pathlib import Path
from typing import BinaryIO, TextIO

from simiam import safe_write

LOCK = ".batch.lock"
SEED = ".seed"         # the folder's secret seed (see :func:`folder_seed`)


class OutputBusy(Exception):
    """Another batch is writing to the same output folder."""


def write_atomic(path: Path, text: str, mode: int | None = None) -> None:
    """Write ``text`` to ``path`` so that readers see the old file or the new one, never a torn one.

    A lone surrogate (a student's non-UTF-8 file name, or text their code sent) is written as ``?``
    rather than failing the write: nothing a student sends can stop a file from being written."""
    safe_write.write_text(path, text, errors="replace", mode=mode, fsync=True)


def write_bytes_atomic(path: Path, data: bytes, mode: int | None = None) -> None:
    """Write ``data`` (a zip of feedback files) to ``path`` as :func:`write_atomic` writes text."""
    safe_write.write_bytes(path, data, mode=mode, fsync=True)


@contextlib.contextmanager
def replacing(path: Path) -> Iterator[BinaryIO]:
    """A binary stream whose bytes replace ``path`` atomically when the block ends (nothing is left if it
    raises): a zip of feedback files written as it is built, never whole in memory."""
    with safe_write.replacing(path, fsync=True) as stream:
        yield stream


def write_json(path: Path, value: object, mode: int | None = None) -> None:
    """Atomically write ``value`` as indented, key-sorted JSON (stable bytes for stable results)."""
    write_atomic(path, json.dumps(value, indent=2, sort_keys=True, allow_nan=False) + "\n", mode)


def read_json(path: Path) -> dict | None:
    """A stored result, or None if it is missing or unreadable (then it is simply graded again)."""
    try:
        value = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return value if isinstance(value, dict) else None


@contextlib.contextmanager
def exclusive(out: Path) -> Iterator[None]:
    """Hold ``out/.batch.lock`` for the whole run; a second batch on the same folder is refused. The lock
    file is removed when the run ends (also after Ctrl-C), so none stays behind to puzzle anyone."""
    out.mkdir(parents=True, exist_ok=True)
    path = out / LOCK
    while True:
        lock = _open_lock(path)
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            lock.close()
            if exc.errno in (errno.EAGAIN, errno.EWOULDBLOCK, errno.EACCES):
                raise OutputBusy(f"another batch is already writing to {out}") from None
            # a file system without locks (some network mounts): carry on unlocked rather than refuse
            lock = _open_lock(path)
            break
        if _same_file(lock, path):
            break
        lock.close()            # the holder before us removed the file after we opened it: lock anew
    try:
        for stale in out.glob(".*.tmp"):   # left by a batch that was killed mid-write
            stale.unlink(missing_ok=True)
        for stale in out.glob("gradescope/*/.*.tmp"):
            stale.unlink(missing_ok=True)
        yield
    finally:
        with contextlib.suppress(OSError):
            path.unlink()       # while still holding it, so a waiting batch re-checks (see above)
        lock.close()


def _open_lock(path: Path) -> TextIO:
    """The lock file, opened to append nothing: created if missing, never through a link planted there."""
    try:
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_APPEND | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise safe_write.LinkRefused(path) from None
        raise
    return os.fdopen(fd, "a")


def _same_file(stream: object, path: Path) -> bool:
    try:
        mine, now = os.fstat(stream.fileno()), os.stat(path)  # type: ignore[attr-defined]
    except OSError:
        return False
    return (mine.st_dev, mine.st_ino) == (now.st_dev, now.st_ino)


def folder_seed(out: Path, given: int | None) -> int:
    """The seed of the grading in ``out``: ``given`` (``--seed N``), else the one stored there by an
    earlier run, else a new secret random one. It is stored in ``out/.seed`` (readable by its owner
    only) so resumes and regrades reuse it; the public default seed is never used for a batch, so the
    hidden goals and worlds cannot be reproduced at home."""
    path = out / SEED
    if given is None:
        try:
            stored = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            stored = None
        seed = stored.get("seed") if isinstance(stored, dict) else None
        if type(seed) is int and 0 <= seed < 2**31:
            return seed
    seed = given if given is not None else secrets.randbelow(2**31)
    write_json(path, {"seed": seed, "set_by": "--seed" if given is not None else "random (secret)"}, 0o600)
    return seed
