"""``moodle_grading_worksheet.csv``, ``moodle_gradebook.csv`` and ``moodle_feedback.zip``: grades and
reports back into Moodle.

The worksheet is the assignment's own offline grading worksheet (Assignment > View all submissions >
Grading action "Upload grading worksheet"; mod/assign/feedback/offline): Moodle finds a row by
``Identifier`` (``Participant <id>``, the participant id of the assignment's "Download all submissions"),
reads ``Grade``, ``Feedback comments`` and ``Last modified (grade)``, and skips a row whose grade is empty
(so a blank never clears a grade), over the maximum, or older than the grade Moodle holds (a grade an
instructor changed in Moodle after this grading is kept unless "Allow updating records that have been
modified more recently in Moodle than in the spreadsheet" is ticked). Only students whose submission came
from a Moodle download have a participant id, so only they are rows.

The gradebook CSV is for Grades > Import > CSV file instead (map ``Email address`` or ``ID number`` to
the user, the grade column to the assignment's grade item): there a blank cell writes "no grade", erasing
one, and an unknown user stops the whole import, so it holds only students with a grade and an e-mail or
ID number.

The zip is for "Upload multiple feedback files in a zip" (mod/assign/feedback/file/importziplib.php):
Moodle reads the first path part shaped ``<anything>_<participant id>_<plugin type>_<plugin name>``;
each student's report is ``<Full Name>_<participant id>_assignsubmission_file_/feedback.html`` as in the
download's own folders (the trailing ``_`` suits Moodle before 4.1 too). The name part has no ``_``
(which would shift the id), ``/``, ``\\``, ``..`` or control characters, and is at most 60 characters.
"""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

from grader.batch.canvas_export import csv_cell
from grader.batch.feedback_zip import write_feedback_zip
from grader.batch.identity import Identity
from grader.batch.posted import Posted, listed, points
from grader.batch.store import write_atomic

WORKSHEET = ["Identifier", "Full name", "Email address", "Grade", "Maximum Grade", "Last modified (grade)",
             "Feedback comments"]
MAX_NAME = 60


def participant_id(identity: Identity) -> str:
    """The student's participant id in the Moodle assignment ("" unless from a Moodle download)."""
    if identity.platform != "moodle":
        return ""
    for candidate in (identity.platform_id, identity.id):
        if candidate.isascii() and candidate.isdigit() and len(candidate) <= 20:
            return candidate
    return ""


def feedback_words(row: Posted, max_score: float | None) -> str:
    """The worksheet's feedback comment: the grader's own words and numbers only (never student text)."""
    if not row.grade or row.result is None:
        return ""
    out_of = f" / {points(max_score)}" if max_score is not None else ""
    late = row.result.get("late")
    penalty = late.get("penalty_points") if isinstance(late, dict) else None
    text = f"Autograder score {row.grade}{out_of}"
    if isinstance(penalty, (int, float)) and not isinstance(penalty, bool) and penalty > 0:
        text += f" after a late penalty of {points(float(penalty))} points"
    if row.result.get("status") == "invalid":
        text += ": the submission could not be graded as submitted"
    return text + ". The full report is the attached feedback file."


def worksheet_csv(rows: list[Posted], max_score: float | None) -> str:
    """The grading worksheet for the students with a Moodle participant id."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(WORKSHEET)
    for row in rows:
        pid = participant_id(row.identity)
        if not pid:
            continue
        timing = row.result.get("timing") if row.result else None
        when = timing.get("graded_at") if isinstance(timing, dict) else None
        modified = when if row.grade and isinstance(when, str) and re.fullmatch(r"[\dT:+\-Z.]{10,40}", when) \
            else "-"
        writer.writerow([f"Participant {pid}", csv_cell(row.identity.name), csv_cell(row.identity.login),
                         row.grade, points(max_score) if max_score is not None else "", modified,
                         feedback_words(row, max_score)])
    return buffer.getvalue()


def gradebook_csv(rows: list[Posted], title: str) -> str:
    """The gradebook import: students with a grade and an e-mail or ID number, nothing blank."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["Email address", "ID number", "Full name", csv_cell(title)])
    for row in rows:
        who = row.identity
        if row.grade and (who.login or who.sis_id):
            writer.writerow([csv_cell(who.login), csv_cell(who.sis_id), csv_cell(who.name), row.grade])
    return buffer.getvalue()


def folder_name(identity: Identity) -> str:
    """``<Full Name>_<participant id>_assignsubmission_file_``, or "" without a participant id."""
    pid = participant_id(identity)
    if not pid:
        return ""
    name = "".join(c if c.isprintable() and c not in "_/\\:*?\"<>|" else " " for c in identity.name)
    name = " ".join(name.replace("..", " ").split())[:MAX_NAME].strip(" .") or "Participant"
    return f"{name}_{pid}_assignsubmission_file_"


def write_moodle(out: Path, rows: list[Posted], pages: dict[str, Path], title: str,
                 max_score: float | None) -> dict:
    """Write the worksheet, the gradebook CSV and the feedback zip; returns their record for batch.json."""
    write_atomic(out / "moodle_grading_worksheet.csv", worksheet_csv(rows, max_score))
    write_atomic(out / "moodle_gradebook.csv", gradebook_csv(rows, title))
    placed, unplaced = write_feedback_zip(
        out / "moodle_feedback.zip", rows, pages,
        lambda row: f"{folder}/feedback.html" if (folder := folder_name(row.identity)) else "",
        "no Moodle participant id")
    in_sheet = [r for r in rows if participant_id(r.identity)]
    left_out = {r.identity.id: "no Moodle participant id" for r in rows if not participant_id(r.identity)}
    blank = {r.identity.id: r.why_blank for r in in_sheet if not r.grade}
    return {"moodle_grading_worksheet.csv": {"rows": len(in_sheet), **listed("not_included", left_out),
                                             **listed("blank", blank)},
            "moodle_feedback.zip": {"entries": placed, **listed("not_included", unplaced)}}
