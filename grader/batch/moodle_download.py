"""Moodle's "Download all submissions" (the zip, or the folder it was extracted to).

Each student's entries start ``<full name>_<participant id>_<plugin type>_<plugin name>``
(moodle ``mod/assign/classes/downloader.php``): as a folder holding the submitted files, ``.../week3/...``
kept (the default; before Moodle 4.1 the folder name ended in ``_``), or flat, the file name appended
after ``_``. Blind marking names the student ``Participant``; online text arrives as ``onlinetext.html``.
The participant id is per assignment (the grading worksheet's "Participant N"), and it is the student id.
"""

from __future__ import annotations

import re

from grader.batch.export_files import Export
from grader.batch.found import Found, rel_clashes
from grader.batch.identity import Identity

TOP = re.compile(
    r"^(?P<prefix>[^/]*?)_(?P<pid>\d+)_(?P<type>assignsubmission|assignfeedback)_"
    r"(?P<plugin>[a-z0-9]+)(?P<rest>(?:_[^/]*)?)$"
)


def looks_like(names: list[str]) -> bool:
    """True when most top-level entries are named as Moodle names a student's submission."""
    matched = sum(1 for n in names if TOP.match(n))
    return matched > 0 and matched * 2 > len(names)


def read_moodle(export: Export) -> tuple[dict[str, Found], list[str]]:
    """The students of a Moodle download by participant id, and the entries that could not be placed."""
    students: dict[str, Found] = {}
    unplaced: list[str] = []
    for entry in export.entries:
        top, _, inside = entry.name.partition("/")
        match = TOP.match(top)
        rest = match["rest"] if match else ""
        # a folder: the rest of the path is the file (pre-4.1 folders end in "_"); flat: after the "_"
        rel = inside if inside and rest in ("", "_") else rest[1:] if not inside and rest[1:] else ""
        if entry.link and not inside and rest in ("", "_"):
            rel = top  # a linked folder in place of the student's: theirs, refused as a link
        if match is None or not rel or match["type"] != "assignsubmission":
            unplaced.append(entry.name)
            continue
        pid = match["pid"]
        name = "" if match["prefix"] == "Participant" else match["prefix"].replace("_", " ")
        found = students.get(pid)
        if found is None:
            found = students[pid] = Found(Identity(id=pid, name=name, platform="moodle", platform_id=pid))
        found.add_file_name(entry.name)
        if match["plugin"] != "file":
            if not any("online text" in n for n in found.notices):
                found.notices.append(
                    "Your online text on Moodle is not graded; only the files you uploaded are."
                )
            continue
        found.members.append((entry.name, rel))
    for found in students.values():
        rel_clashes(found)
    return students, unplaced
