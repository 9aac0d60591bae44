"""``canvas_import.csv`` and ``canvas_feedback.zip``: grades and reports back into Canvas.

The CSV is Canvas's own gradebook import format (Grades > Import, instructure/canvas-lms
``lib/gradebook_importer.rb``): ``Student,ID,SIS User ID,SIS Login ID,Section,<Assignment (id)>``, then the
``    Points Possible`` row, then one row per student. Canvas matches a row by ``ID`` (the Canvas user id),
then SIS User ID, SIS Login ID, name; it matches the column by the id in ``Title (123)``, else by exact
title, else offers to create an assignment with the Points Possible given here.

The zip is for Canvas's "Re-Upload Submissions" (the assignment's column menu in the Gradebook, offered
once submissions were downloaded): Canvas reads each entry's first two all-digit ``_``-separated parts as
the user id and the id of a file that student submitted (``Assignment#infer_comment_context_from_filename``)
and attaches the entry to that submission as a comment; entries it cannot place are skipped. So each
student's report is named ``<name letters>_<user id>_<file id>_feedback.html`` after a file of their
Canvas download; the name part is letters only (never digits, ``_``, ``/``, ``..`` or control characters,
whatever the student's name holds), so it can never be read as an id.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

from grader.batch.feedback_zip import write_feedback_zip
from grader.batch.identity import Identity
from grader.batch.posted import Posted, listed, points
from grader.batch.store import write_atomic

HEADER = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"]
POINTS_POSSIBLE = "    Points Possible"
MAX_SLUG = 40


def csv_cell(value: str) -> str:
    """A text cell a spreadsheet will not run (``=``, ``+``, ``-``, ``@`` first get a ``'``); Canvas
    reads names and ids only to match a student, by ID first."""
    return "'" + value if value[:1] in ("=", "+", "-", "@", "\t", "\r") else value


def canvas_user_id(identity: Identity) -> str:
    """The student's Canvas user id ("" unless the submission came from a Canvas download)."""
    if identity.platform != "canvas":
        return ""
    for candidate in (identity.platform_id, identity.id):
        if candidate.isascii() and candidate.isdigit() and len(candidate) <= 20:
            return candidate
    return ""


def canvas_csv(rows: list[Posted], title: str, max_score: float | None) -> str:
    """The import CSV: every row's grade in the column ``title`` with ``max_score`` points possible."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([*HEADER, csv_cell(title)])
    writer.writerow([POINTS_POSSIBLE, "", "", "", "", points(max_score) if max_score is not None else ""])
    for row in rows:
        who = row.identity
        # a class folder's id is the institution's student id: Canvas matches it as the SIS User ID
        sis = who.sis_id or (who.id if who.platform == "folder" else "")
        writer.writerow([csv_cell(who.name or who.id), canvas_user_id(who), csv_cell(sis),
                         csv_cell(who.login), csv_cell(who.section), row.grade])
    return buffer.getvalue()


def attachment_id(identity: Identity) -> str:
    """The id of a file the student submitted, from the names of their Canvas download ("" if none):
    Canvas takes the first two all-digit parts of a name as user id and file id."""
    user = canvas_user_id(identity)
    for name in sorted(identity.files):
        digits = [part for part in name.split("_") if part.isascii() and part.isdigit()]
        if len(digits) >= 2 and digits[0] == user and len(digits[1]) <= 20:
            return digits[1]
    return ""


def entry_name(identity: Identity) -> str:
    """``<letters>_<user id>_<file id>_feedback.html``, or "" when Canvas could not place it."""
    user, file_id = canvas_user_id(identity), attachment_id(identity)
    if not user or not file_id:
        return ""
    letters = "".join(c for c in (identity.name or "").casefold() if c.isalpha())[:MAX_SLUG] or "student"
    return f"{letters}_{user}_{file_id}_feedback.html"


def write_canvas(out: Path, rows: list[Posted], pages: dict[str, Path], title: str,
                 max_score: float | None) -> dict:
    """Write ``canvas_import.csv`` and ``canvas_feedback.zip``; returns their record for batch.json:
    the students left blank and why, and those with no feedback entry and why."""
    write_atomic(out / "canvas_import.csv", canvas_csv(rows, title, max_score))
    blank = {r.identity.id: r.why_blank for r in rows if not r.grade}
    placed, unplaced = write_feedback_zip(out / "canvas_feedback.zip", rows, pages,
                                          lambda row: entry_name(row.identity),
                                          "no file of a Canvas download to attach the report to")
    return {"canvas_import.csv": {"rows": len(rows), "title": title, **listed("blank", blank)},
            "canvas_feedback.zip": {"entries": placed, **listed("not_included", unplaced)}}
