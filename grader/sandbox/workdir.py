"""The worker's private copy of the spliced submission.

The session copies the spliced folder (the grader's splice output) into a fresh directory before the first
worker starts: only regular top-level files (no symlinks, no sub-folders, each at most MAX_FILE_BYTES), owned
by the grader, read-only to the worker, and readable only by the worker's own group when the grader runs as
root. bubblewrap binds this copy read-only at /submission; a plain subprocess reads it in place (the parent
directory is traversable, 0711, but not listable). It is removed when the session closes.

The copy goes into the temporary folder (TMPDIR) unless a plain subprocess reads it in place under a
dedicated uid that cannot enter that folder (TMPDIR inside a folder only root can open): then into the first
shared temporary folder that uid can enter (`temp_folder`). Where there is none, the session refuses to
start rather than let the worker fail to import its own library and blame the student's files.
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
from pathlib import Path

from grader.sandbox.errors import SandboxUnavailable
from grader.sandbox.leftovers import UID_MARK
from grader.sandbox.reach import enterable

MAX_FILE_BYTES = 512 * 1024
MAX_FILES = 64
# Where the copies go when TMPDIR is out of the worker's reach: the machine's shared temporary folders, which
# every uid may enter; the copy inside stays readable only by the worker's group.
SHARED_TEMP = ("/tmp", "/var/tmp", "/dev/shm")
PRIVATE = "private"   # beside the copy: a plain-subprocess worker's own writable folder (its uid's, 0700)


def temp_folder(other_uid: bool) -> Path:
    """The folder for copies a worker reads in place: TMPDIR (tempfile.gettempdir()), unless `other_uid`
    (the reader is a uid without privileges) cannot enter it; then the first of SHARED_TEMP it can enter.
    TMPDIR again when none can be entered (the caller says so)."""
    here = Path(tempfile.gettempdir())
    if not other_uid or enterable(here):
        return here
    return next((Path(p) for p in SHARED_TEMP if os.path.isdir(p) and enterable(p)), here)


class WorkCopy:
    """A private, read-only copy of `source` at `self.path`; `skipped` lists what was not copied and why.

    With `gid` (the worker's dedicated group, grader running as root) the copy is readable by that group
    only, so a concurrent worker of another submission cannot read it even without bubblewrap. With
    `in_place` too (a plain subprocess, which reads the copy where it is), the copy goes where that uid can
    enter (temp_folder); SandboxUnavailable if it cannot enter any temporary folder.
    """

    def __init__(self, source: Path, gid: int | None = None, in_place: bool = False) -> None:
        reader_outside = gid is not None and in_place
        self._root = Path(tempfile.mkdtemp(prefix="simiam-work-", dir=temp_folder(reader_outside)))
        self._root.chmod(0o711)
        if reader_outside and not enterable(self._root):
            self.remove()
            raise SandboxUnavailable(
                f"the sandbox's own uid cannot enter any temporary folder here ({self._root.parent} and "
                f"{', '.join(SHARED_TEMP)} are closed to other users), so it could not read the copy of "
                "the submission: set TMPDIR to a folder every user may enter, or install bubblewrap")
        self.path = self._root / "submission"
        self.path.mkdir()
        self.skipped: list[str] = []
        entries = sorted(os.scandir(source), key=lambda e: e.name) if source.is_dir() else []
        for entry in entries:
            info = entry.stat(follow_symlinks=False)
            if not stat.S_ISREG(info.st_mode):
                self.skipped.append(f"{entry.name}: not a regular file")
            elif info.st_size > MAX_FILE_BYTES:
                self.skipped.append(f"{entry.name}: larger than {MAX_FILE_BYTES // 1024} kB")
            elif len(os.listdir(self.path)) >= MAX_FILES:
                self.skipped.append(f"{entry.name}: more than {MAX_FILES} files")
            else:
                target = self.path / entry.name
                with open(entry.path, "rb") as src, open(target, "xb") as dst:
                    shutil.copyfileobj(src, dst)
                target.chmod(0o644)
        self.path.chmod(0o755)
        if gid is not None:
            # who to clean up after if this grading process is killed (grader.sandbox.leftovers)
            (self._root / UID_MARK).write_text(str(gid))
            if in_place:   # the worker's own HOME and TMPDIR, removed with the copy (leftovers)
                private = self._root / PRIVATE
                private.mkdir(mode=0o700)
                os.chown(private, gid, gid)
            for path in (self.path, *self.path.iterdir()):
                os.chown(path, 0, gid)
                path.chmod(0o750 if path.is_dir() else 0o640)

    def remove(self) -> None:
        shutil.rmtree(self._root, ignore_errors=True)
