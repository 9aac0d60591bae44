"""What this system offers the sandbox, and the "local check only" note when part of it is missing.

On Linux with bubblewrap every defence is there. Elsewhere (macOS, a Linux without bubblewrap or user
namespaces, an interpreter built without `resource` or `fcntl`), `grade` still runs: student code goes to a
plain subprocess with the limits the system offers, and every result says what was missing, starting
"local check only:". Official grading (the instructor's Linux machine) runs the full sandbox.

A platform's official grading (grader.platforms.official) may run where bubblewrap cannot create its
namespaces (a Docker container with the default capabilities) or without root (Coursera): there the note
starts "official grading, on a platform that does not offer the full sandbox:" instead, says what held,
and points the course staff to docs/platforms.md.
"""

from __future__ import annotations

import importlib
import os
import sys

LOCAL_ONLY = "local check only"
OFFICIAL_PARTIAL = "official grading, on a platform that does not offer the full sandbox"


def has_module(name: str) -> bool:
    """True if `name` imports here (a module set to None in sys.modules counts as missing)."""
    try:
        importlib.import_module(name)
    except ImportError:
        return False
    return True


def is_root() -> bool:
    """True if this process runs as root (False where the system has no uids: Windows)."""
    geteuid = getattr(os, "geteuid", None)
    return geteuid is not None and geteuid() == 0


def missing(bwrap_ok: bool, bwrap_why: str = "", official: bool = False) -> list[str]:
    """What the worker goes without on this system, one phrase each (empty: nothing is missing).
    `official`: on a platform, where "your user" would be the grader's (what it can read is said after)."""
    from grader.inside.seccomp import available as seccomp_available

    out = []
    if not bwrap_ok:
        out.append(f"no bubblewrap sandbox ({bwrap_why or 'not available here'})" if official else
                   f"no bubblewrap sandbox ({bwrap_why or 'not available here'}): your code can read "
                   "what your user can read")
    if not has_module("resource"):
        out.append("no kernel limits on memory, CPU time, processes or file size (Python's resource module "
                   "is missing); the grader's time limits per call and per submission still hold")
    if not seccomp_available():
        out.append("no seccomp filter (Linux only): network access and new processes are not blocked")
    if not has_module("fcntl"):
        out.append("no fcntl module: printed output may be cut short in the feedback")
    return out


def local_only_note(items: list[str]) -> str:
    """The sentence every result carries when `items` (from `missing`) is not empty."""
    return (f"{LOCAL_ONLY}: your code ran in a plain subprocess on {sys.platform} with "
            + "; ".join(items) + ". Official grading runs it in the full sandbox.")


def official_note(items: list[str]) -> str:
    """The sentence a platform's official result carries when `items` (from `missing`) is not empty: this
    *is* the official grading, so it says what ran, not that the full sandbox runs elsewhere."""
    return (f"{OFFICIAL_PARTIAL}: your code ran in a plain subprocess on {sys.platform}, with the strongest "
            "isolation this grading machine allows; missing: " + "; ".join(items) + ". This grade is "
            "official; the course staff can give the grading machine the full sandbox (docs/platforms.md).")


LIMIT_NAMES = ("core dumps", "CPU time", "memory", "file size", "open files", "processes")


def with_refused_limits(note: str, refused: object) -> str:
    """`note` with the kernel limits the worker's system refused (from its ready message, sent before any
    student code; only known names are kept) put first, as "local check only: ..."."""
    names = [n for n in LIMIT_NAMES if isinstance(refused, list) and n in refused]
    if not names:
        return note
    first = OFFICIAL_PARTIAL if note.startswith(OFFICIAL_PARTIAL + ": ") else LOCAL_ONLY
    rest = note[len(first) + 2:] if note.startswith(first + ": ") else note
    return f"{first}: this system refused these kernel limits: {', '.join(names)}. {rest}"
