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
