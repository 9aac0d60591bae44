"""What a uid without privileges can reach here: the sandbox's dedicated uid where there is no bubblewrap.

As root, a plain-subprocess worker drops to a uid of its own (grader.sandbox.isolation) with no supplementary
groups, and no file is owned by it or names it in an ACL, so only the permission bits for "others" open a
path to it: every folder from / down must let others enter (o+x), and the path itself let them read (o+r).
A checkout, a virtual environment or a TMPDIR inside a folder only its owner can open (0700, a home folder
on many systems) is therefore out of its reach however readable the files inside are. Under bubblewrap none
of this matters: the sandbox binds what the worker needs at new places whose parents it creates open.

One rule, used for where the worker's copies go (grader.sandbox.workdir), what the isolation note says the
worker can read, and whether the Python environment must be preloaded (grader.sandbox.isolation).
"""

from __future__ import annotations

import os
import stat
from pathlib import Path


def enterable(folder: str | Path) -> bool:
    """True if others may pass through `folder` and every folder above it (o+x all the way down)."""
    path = Path(folder).resolve()
    try:
        return all(os.stat(p).st_mode & stat.S_IXOTH for p in (*reversed(path.parents), path))
    except OSError:
        return False


def readable(path: str | Path) -> bool:
    """True if others may read `path` (a folder: list and enter it): every folder above it enterable too."""
    path = Path(path).resolve()
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return False
    needed = stat.S_IROTH | (stat.S_IXOTH if stat.S_ISDIR(mode) else 0)
    return mode & needed == needed and enterable(path.parent)


def executable(path: str | Path) -> bool:
    """True if others may run `path`: the folders down to it enterable, and the file it names (after links,
    whose folders must be enterable too) a regular file with o+x."""
    path = Path(path).absolute()
    target = path.resolve()
    try:
        mode = os.stat(target).st_mode
    except OSError:
        return False
    return (stat.S_ISREG(mode) and bool(mode & stat.S_IXOTH) and enterable(path.parent)
            and enterable(target.parent))
