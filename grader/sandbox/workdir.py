"""The worker's private copy of the spliced submission.

The session copies the spliced folder (the grader's splice output) into a fresh directory before the first
worker starts: only regular top-level files (no symlinks, no sub-folders, each at most MAX_FILE_BYTES), owned
by the grader, read-only to the worker, and readable only by the worker's own group when the grader runs as
root. bubblewrap binds this copy read-only at /submission; a plain subprocess reads it in place (the parent
directory is traversable, 0711, but not listable). It is removed when the session closes.
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
from pathlib import Path

from grader.sandbox.leftovers import UID_MARK

MAX_FILE_BYTES = 512 * 1024
MAX_FILES = 64


class WorkCopy:
    """A private, read-only copy of `source` at `self.path`; `skipped` lists what was not copied and why.

    With `gid` (the worker's dedicated group, grader running as root) the copy is readable by that group
    only, so a concurrent worker of another submission cannot read it even without bubblewrap.
    """

    def __init__(self, source: Path, gid: int | None = None) -> None:
        self._root = Path(tempfile.mkdtemp(prefix="simiam-work-"))
        self._root.chmod(0o711)
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
            for path in (self.path, *self.path.iterdir()):
                os.chown(path, 0, gid)
                path.chmod(0o750 if path.is_dir() else 0o640)

    def remove(self) -> None:
        shutil.rmtree(self._root, ignore_errors=True)
