"""Process trees of grading processes: kill one with everything it started, and say why one died.

A grading process starts sandboxed student workers (bubblewrap, which starts Python). Killing only the
grading process would leave those running, so a timeout freezes and kills the whole tree, found through
/proc by parent id (Linux; elsewhere only the process group is reached).
"""

from __future__ import annotations

import os
import signal


def die_with_parent() -> None:
    """Ask Linux to SIGKILL this process when the runner dies (even by SIGKILL), so no orphan grades on."""
    try:
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)       # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() == 1:                            # the runner died before the request took effect
        os._exit(1)


def _descendants(pid: int) -> list[int]:
    """Every process below ``pid`` (Linux /proc scan; empty elsewhere)."""
    children: dict[int, list[int]] = {}
    try:
        entries = os.listdir("/proc")
    except OSError:
        return []
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as stream:
                ppid = int(stream.read().rsplit(b")", 1)[1].split()[1])
        except (OSError, IndexError, ValueError):
            continue
        children.setdefault(ppid, []).append(int(entry))
    found, todo = [], [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def kill_tree(pid: int) -> None:
    """SIGKILL a process, its process group and all its descendants (frozen first so none can fork)."""
    seen: set[int] = set()
    for _ in range(3):                       # stop, re-scan for anything forked meanwhile, stop again
        new = [p for p in [pid, *_descendants(pid)] if p not in seen]
        if not new:
            break
        for p in new:
            _signal(p, signal.SIGSTOP)
        seen.update(new)
    try:
        os.killpg(pid, signal.SIGKILL)
    except OSError:
        pass
    for p in seen:
        _signal(p, signal.SIGKILL)


def _signal(pid: int, sig: int) -> None:
    try:
        os.kill(pid, sig)
    except OSError:
        pass


def exit_reason(code: int | None) -> str:
    """Plain words for a child's exit code."""
    if code is None:
        return "the grading process stopped answering"
    if code < 0:
        try:
            name = signal.Signals(-code).name
        except ValueError:
            name = f"signal {-code}"
        hint = " (out of memory?)" if -code == signal.SIGKILL else ""
        return f"the grading process was killed by {name}{hint}"
    return f"the grading process exited with status {code}"
