"""Canvas's "Download Submissions" zip (or the folder it was extracted to).

Every entry sits at the top level, named ``<name>[_LATE]_<user id>_<attachment id>_<display name>`` for
an uploaded file, ``<name>[_LATE]_<user id>_text.html`` / ``_link.html`` for a text entry or a URL
(canvas-lms ``lib/content_zipper.rb``: the name is the lower-cased sortable name with non-word characters
removed; anonymous grading has no name and ``anon_<id>``; ``LATE`` marks work Canvas counted late). Canvas
renames a re-uploaded file whose name already existed ``name-1.py``; such a name is read as the course
file it stands for when the student has no other file of that name. A zip the student uploaded stays
nested and is read later as the student's own zip.
"""

from __future__ import annotations

import re

from grader.batch.export_files import Export
from grader.batch.found import Found, rel_clashes
from grader.batch.identity import Identity
from grader.batch.submissions import STUDENT_FILES

ENTRY = re.compile(
    r"^(?:(?P<name>[^/]*?)_)??(?:(?P<late>late)_)?(?P<uid>anon_[0-9a-z]+|\d+)_"
    r"(?:(?P<att>\d+)_(?P<file>[^/]+)|(?P<kind>text|link)\.html)$",
    re.IGNORECASE,
)
REUPLOAD = re.compile(r"^(?P<base>[^.]*?)-\d+(?P<ext>\..*)?$")


def looks_like(names: list[str], export: Export) -> bool:
    """True when most top-level entries are files named as Canvas names them."""
    files = {e.name for e in export.entries if "/" not in e.name}
    matched = sum(1 for n in names if n in files and ENTRY.match(n))
    return matched > 0 and matched * 2 > len(names)


def read_canvas(export: Export) -> tuple[dict[str, Found], list[str]]:
    """The students of a Canvas download by Canvas user id, and the entries that could not be placed."""
    students: dict[str, Found] = {}
    unplaced: list[str] = []
    for entry in export.entries:
        match = ENTRY.match(entry.name) if "/" not in entry.name else None
        if match is None:
            unplaced.append(entry.name)
            continue
        # Canvas's anonymous ids are case-sensitive (anon_a1B2c and anon_A1b2C are two students)
        uid = "anon_" + match["uid"][5:] if match["uid"].lower().startswith("anon_") else match["uid"]
        found = students.get(uid)
        if found is None:
            found = students[uid] = Found(
                Identity(id=uid, name=match["name"] or "", platform="canvas", platform_id=uid)
            )
        if match["late"] and not found.identity.late_flag:
            found.identity = _late(found.identity)
        found.add_file_name(entry.name)
        if match["kind"]:
            what = "text entry" if match["kind"].lower() == "text" else "website URL"
            found.notices.append(f"Your {what} on Canvas is not graded; only the files you uploaded are.")
            continue
        found.members.append((entry.name, match["file"]))
    for found in students.values():
        _undo_reupload_names(found)
        rel_clashes(found)
    return students, unplaced


def _late(identity: Identity) -> Identity:
    import dataclasses

    return dataclasses.replace(identity, late_flag=True)


def _undo_reupload_names(found: Found) -> None:
    """``go_to_goal-1.py`` -> ``go_to_goal.py`` when that is a course file the student has no other
    entry for (Canvas's renaming of a re-upload); with both present, :func:`rel_clashes` holds them."""
    renamed = []
    for name, rel in found.members:
        match = REUPLOAD.match(rel)
        plain = f"{match['base']}{match['ext'] or ''}" if match else rel
        renamed.append((name, plain if rel not in STUDENT_FILES and plain in STUDENT_FILES else rel))
    found.members = renamed
