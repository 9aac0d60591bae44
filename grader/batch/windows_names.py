"""Names in a submission that cannot be files on Windows, and names Windows takes for one another.

A student's zip or folder may come from any system, and the files of a submission are written again (by
the platform's intake, the batch's grading processes) on the grader's machine, which may run Windows.
There, a name is a device whatever its extension (``CON``, ``aux.py``, ``nul.txt``, ``COM1``...), a
trailing dot or space is dropped (``go_to_goal.py.`` is ``go_to_goal.py``), ``<>:"|?*`` and ``\\`` are not
allowed, and names differing only by case are one file. :func:`problem` says what is wrong with one name;
:func:`same_file_key` gives the key two paths share when Windows would make them one file;
:func:`leave_out` drops the files whose path cannot be written there, each said in a note (the grader uses
only the course's fixed file names, none of which has such a problem).
"""

from __future__ import annotations

DEVICES = frozenset({"con", "prn", "aux", "nul", *(f"com{i}" for i in range(10)),
                     *(f"lpt{i}" for i in range(10))})
FORBIDDEN = frozenset('<>:"|?*\\')


def problem(name: str) -> str | None:
    """Why `name` (one path component) cannot be a file or folder name on Windows, or None."""
    if name != name.rstrip(". "):
        return "ends with a dot or a space, which Windows drops"
    if name.split(".", 1)[0].rstrip(" ").casefold() in DEVICES:
        return "is a device name on Windows (CON, PRN, AUX, NUL, COM0-9, LPT0-9, with any extension)"
    bad = sorted(FORBIDDEN.intersection(name))
    if bad:
        return f"holds {' '.join(bad)}, which Windows does not allow in a name"
    return None


def same_file_key(rel: str) -> str:
    """The key two slash-separated paths share when Windows would store them as one file: case folded,
    trailing dots and spaces dropped from each component."""
    return "/".join(part.rstrip(". ").casefold() for part in rel.split("/"))


def leave_out(files: dict[str, bytes], notes: list[str]) -> dict[str, bytes]:
    """`files` without those whose path has a component with a `problem`; one note per file left out."""
    kept = {}
    for rel, data in files.items():
        why = next((f"{part!r} {reason}" for part in rel.split("/") if (reason := problem(part))), None)
        if why is None:
            kept[rel] = data
        else:
            notes.append(f"{rel}: {why}, so it cannot be written everywhere the grader runs; it was left out")
    return kept
