"""Wrong implementations the batch tests must catch (each test proves it can fail on one of these)."""

from __future__ import annotations

import hashlib
import json
import os
import signal
import zipfile
from pathlib import Path


def naive_read_zip(path: Path, limits: object = None) -> dict[str, bytes]:
    """Reads every entry as it is: no path, symlink, size, count or ratio checks."""
    with zipfile.ZipFile(path) as archive:
        return {info.filename: archive.read(info) for info in archive.infolist() if not info.is_dir()}


def cache_key_ignoring_seed(week: int, seed: int, hidden: bool, submission_sha256: str, grader: str) -> str:
    """Forgets the seed: a rerun with another seed would wrongly reuse old results."""
    material = json.dumps({"week": week, "hidden": hidden, "submission": submission_sha256, "grader": grader})
    return hashlib.sha256(material.encode()).hexdigest()


def kill_only_the_process(pid: int) -> None:
    """Kills the grading process but leaves the sandboxed workers it started running."""
    os.kill(pid, signal.SIGKILL)


def csv_cell_as_is(value: object) -> object:
    """Lets a formula such as =HYPERLINK(...) through to the spreadsheet."""
    return value


def student_stem_as_id(student_id: str) -> str:
    """The old output name: the id itself, suffixed for the batch's own names. "batch" and
    "batch.student" share a file, a 255-byte id cannot be written, "Alice" and "alice" collide on a
    case-insensitive disk."""
    reserved = {"batch", "summary", "gradebook", "gradescope"}
    return f"{student_id}.student" if student_id.lower() in reserved else student_id


def accept_every_name(*_args: object) -> None:
    """No check of ids or paths: names that cannot exist on disk go on to the grading process."""


def keep_scratch(_scratch: object, _kill: object = None) -> None:
    """Leaves a killed grading process's temporary folder (student code inside) where it is."""


def no_bound(result: dict, limit: int = 0) -> dict:
    """Stores whatever the worker made the result grow to."""
    return result


def public_seed(_out: object, given: int | None) -> int:
    """The old default: the public seed, so hidden goals and worlds can be reproduced at home."""
    return 2014 if given is None else given


def blame_the_oldest(held: list, outcome: dict) -> tuple[list, list]:
    """Blames the oldest task a grading process held for its death, though the next one may have caused it."""
    import time
    return [(held[0].task, {**outcome, "seconds": time.monotonic() - held[0].sent})], [e.task for e in held[1:]]
