"""What a worker can leave behind outside its own process tree, and how the grader removes it.

In bubblewrap mode nothing outlives the sandbox: /tmp is a private tmpfs, System V IPC lives in the
sandbox's own IPC namespace. In plain subprocess mode a worker running under its own dedicated uid (the
grader runs as root) gets a private folder of its own as HOME and TMPDIR (grader.sandbox.workdir, removed
with the work copy), but it can still leave files in any folder of the machine that uid may write, and
System V IPC objects (shared memory, message queues, semaphore sets); POSIX shared memory, semaphores and
message queues are files in /dev/shm and /dev/mqueue.

Which folders that uid may write is found, not listed (issue 30 item 3: a note left in /run/lock, outside
the four folders once listed, was read by a student graded later): `writable_folders` walks every writable
mount once per grading process (read-only mounts and the kernel's pseudo file systems skipped, never
crossing into another mount, never entering a folder other users cannot enter, since a fresh uid cannot
reach anything below it), bounded by WALK_SECONDS, and keeps the folders other users may write (o+wx).
A fresh uid owns nothing, so everything it left is an entry it owns in one of those folders (with all it
holds). `remove_files_of` removes exactly those, `remove_ipc_of` its IPC objects, when the worker ends;
when a grading process is killed before it could, the batch pool sweeps the uids it recorded
(:func:`sweep_scratch`, given the kill). What the walk does not see: access granted by ACLs, and folders
made writable to all after the walk; a walk cut short by its bound keeps the folders found so far and
FALLBACK. Without a dedicated uid (the grader does not run as root) nothing can tell the student's
leftovers from the user's own, so nothing is removed: the isolation note says so.
"""

from __future__ import annotations

import ctypes
import functools
import os
import shutil
import stat
import time
from collections.abc import Callable, Iterable
from pathlib import Path

from grader.sandbox.capabilities import is_root

UID_MARK = "uid"          # a WorkCopy's root records the dedicated uid of its workers in this file
_IPC_RMID = 0
_SYSV = (("shm", "shmctl", 7), ("msg", "msgctl", 7), ("sem", "semctl", 4))   # /proc/sysvipc, uid column


def sysv_ipc_of(uid: int) -> list[tuple[str, int]]:
    """``(kind, id)`` of every System V IPC object owned by ``uid`` (Linux /proc/sysvipc)."""
    found = []
    for kind, _call, uid_column in _SYSV:
        try:
            lines = Path(f"/proc/sysvipc/{kind}").read_text().splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            fields = line.split()
            try:
                if int(fields[uid_column]) == uid:
                    found.append((kind, int(fields[1])))
            except (IndexError, ValueError):
                continue
    return found


def remove_ipc_of(uid: int) -> list[tuple[str, int]]:
    """Remove the System V IPC objects of ``uid``; returns what was removed."""
    objects = sysv_ipc_of(uid)
    if not objects:
        return []
    try:
        libc = ctypes.CDLL(None, use_errno=True)
    except OSError:
        return []
    calls = {kind: call for kind, call, _ in _SYSV}
    removed = []
    for kind, ident in objects:
        fn = getattr(libc, calls[kind])
        result = fn(ident, 0, _IPC_RMID, None) if kind == "sem" else fn(ident, _IPC_RMID, None)
        if result == 0:
            removed.append((kind, ident))
    return removed


FALLBACK = ("/tmp", "/var/tmp", "/dev/shm", "/dev/mqueue", "/run/lock", "/var/lock")  # kept if the walk stops
WALK_SECONDS = 20.0   # the walk's bound (about 0.3 s of CPU for 19,000 folders, measured on a loaded machine)
# kernel and virtual file systems: nothing a uid writes there is a file left for the next student
_PSEUDO = frozenset(("proc", "sysfs", "cgroup", "cgroup2", "devpts", "securityfs", "debugfs", "tracefs",
                     "pstore", "bpf", "configfs", "fusectl", "binfmt_misc", "autofs", "nsfs", "efivarfs",
                     "selinuxfs", "rpc_pipefs", "nfsd"))


def writable_mounts(mountinfo: str = "/proc/self/mountinfo") -> list[str]:
    """The mount points of this system that are mounted read-write, pseudo file systems left out."""
    try:
        lines = Path(mountinfo).read_text().splitlines()
    except OSError:
        return ["/"]
    found = []
    for line in lines:
        fields = line.split()
        try:
            cut = fields.index("-")
            point, options, kind, super_options = fields[4], fields[5], fields[cut + 1], fields[cut + 3]
        except (ValueError, IndexError):
            continue
        if kind in _PSEUDO or "ro" in options.split(",") or "ro" in super_options.split(","):
            continue
        point = point.encode().decode("unicode_escape")  # mountinfo writes a space as \040
        if point not in found:
            found.append(point)
    return found


def _others_may(mode: int, bits: int) -> bool:
    return mode & bits == bits


def walk_writable(mounts: Iterable[str], seconds: float = WALK_SECONDS) -> tuple[list[str], bool]:
    """(the folders on `mounts` that other users may write, whether the walk finished within `seconds`).
    Each mount is walked without crossing into another and without entering a folder others cannot enter."""
    deadline = time.monotonic() + seconds
    found: list[str] = []
    for mount in mounts:
        try:
            top = os.stat(mount, follow_symlinks=False)
        except OSError:
            continue
        if not stat.S_ISDIR(top.st_mode) or not _others_may(top.st_mode, 0o001):
            continue
        if _others_may(top.st_mode, 0o003) and mount not in found:
            found.append(mount)
        todo = [mount]
        while todo:
            if time.monotonic() > deadline:
                return found, False
            folder = todo.pop()
            try:
                with os.scandir(folder) as entries:
                    for entry in entries:
                        if not entry.is_dir(follow_symlinks=False):
                            continue
                        info = entry.stat(follow_symlinks=False)
                        if info.st_dev != top.st_dev or not _others_may(info.st_mode, 0o001):
                            continue      # another mount (walked on its own), or closed to other users
                        if _others_may(info.st_mode, 0o003):
                            found.append(entry.path)
                        todo.append(entry.path)
            except OSError:
                continue
    return found, True


@functools.lru_cache(maxsize=1)
def writable_folders() -> tuple[str, ...]:
    """Every folder of this machine a fresh uid may write (walked once per process; see the module doc)."""
    found, finished = walk_writable(writable_mounts())
    extra = [] if finished else [p for p in FALLBACK if os.path.isdir(p) and p not in found]
    return tuple(found + extra)


def remove_files_of(uid: int, folders: Iterable[str] | None = None) -> list[str]:
    """Delete what `uid` left in `folders` (default: every folder it could write, `writable_folders`):
    each entry it owns, a folder with all it holds, a link as the link. Returns what was removed."""
    removed = []
    for root in writable_folders() if folders is None else folders:
        try:
            entries = list(os.scandir(root))
        except OSError:
            continue
        for entry in entries:
            try:
                if entry.stat(follow_symlinks=False).st_uid != uid:
                    continue
                if entry.is_dir(follow_symlinks=False):
                    shutil.rmtree(entry.path, ignore_errors=True)
                else:
                    os.unlink(entry.path)
                removed.append(entry.path)
            except OSError:
                pass
    return removed


def remove_everything_of(uid: int, kill: Callable[[int], object]) -> None:
    """Kill ``uid``'s processes with `kill` (grader.sandbox.runner.kill_uid), then remove its files in the
    folders it could write and its IPC objects."""
    kill(uid)
    remove_files_of(uid)
    remove_ipc_of(uid)


def recorded_uids(scratch: Path) -> list[int]:
    """The dedicated uids recorded by the work copies under ``scratch`` (a grading process's temp dir)."""
    uids = []
    for mark in scratch.glob(f"simiam-work-*/{UID_MARK}"):
        try:
            uids.append(int(mark.read_text()))
        except (OSError, ValueError):
            continue
    return uids


def sweep_scratch(scratch: Path, kill: Callable[[int], object]) -> None:
    """After a grading process ended (or was killed): clean up after the uids of the workers it started
    (their processes killed with `kill`: grader.sandbox.runner.kill_uid) and delete its whole temporary
    folder, student code included."""
    for uid in recorded_uids(scratch) if is_root() else []:
        remove_everything_of(uid, kill)
    shutil.rmtree(scratch, ignore_errors=True)
