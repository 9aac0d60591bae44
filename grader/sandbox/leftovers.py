"""What a worker can leave behind outside its own process tree, and how the grader removes it.

In bubblewrap mode nothing outlives the sandbox: /tmp is a private tmpfs, System V IPC lives in the
sandbox's own IPC namespace. In plain subprocess mode a worker running under its own dedicated uid (the
grader runs as root) can leave files in the machine's shared writable folders and System V IPC objects
(shared memory, message queues, semaphore sets); POSIX shared memory, semaphores and message queues are
files in /dev/shm and /dev/mqueue. All of them are removed by uid when the worker ends
(:func:`remove_ipc_of` here, ``runner.remove_files_of`` for files), and when a grading process is killed
before it could do so, the batch pool sweeps the uids it recorded (:func:`sweep_scratch`). Without a
dedicated uid (the grader does not run as root) nothing can tell the student's leftovers from the user's
own, so nothing is removed: the isolation note says so.
"""

from __future__ import annotations

import ctypes
import shutil
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


def remove_everything_of(uid: int) -> None:
    """Kill ``uid``'s processes, then remove its files in shared folders and its IPC objects."""
    from grader.sandbox.runner import kill_uid, remove_files_of

    kill_uid(uid)
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


def sweep_scratch(scratch: Path) -> None:
    """After a grading process ended (or was killed): clean up after the uids of the workers it started
    and delete its whole temporary folder, student code included."""
    for uid in recorded_uids(scratch) if is_root() else []:
        remove_everything_of(uid)
    shutil.rmtree(scratch, ignore_errors=True)
