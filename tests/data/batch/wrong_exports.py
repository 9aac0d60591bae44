"""Wrong grade exporters the tests of tests/batch/test_batch_grades_back.py must catch (kept as data)."""

from __future__ import annotations

import csv
import io

from grader.batch.posted import Posted, points, posted


def canvas_csv_without_points_possible(rows: list[Posted], title: str, max_score: float | None) -> str:
    """Canvas's import without the ``    Points Possible`` row: Canvas then reads the first student as it."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["Student", "ID", "SIS User ID", "SIS Login ID", "Section", title])
    for row in rows:
        who = row.identity
        writer.writerow([who.name or who.id, who.platform_id, who.sis_id, who.login, who.section, row.grade])
    return buffer.getvalue()


def posted_before_penalty(sid: str, result: dict | None, max_score: float | None) -> Posted:
    """The score before the late penalty (``late.score_before``): the late student keeps full marks."""
    row = posted(sid, result, max_score)
    late = result.get("late") if isinstance(result, dict) else None
    if isinstance(late, dict) and row.grade:
        return Posted(row.identity, points(float(late["score_before"])), row.why_blank, row.result)
    return row


def posted_zero_when_blank(sid: str, result: dict | None, max_score: float | None) -> Posted:
    """An invented 0 for a held, timed-out or missing student."""
    row = posted(sid, result, max_score)
    return row if row.grade else Posted(row.identity, "0", "", row.result)


def moodle_folder_with_raw_name(identity) -> str:      # noqa: ANN001 - a stand-in for folder_name
    """The student's name as given: an ``_`` in it shifts Moodle's participant id onto the wrong part."""
    pid = identity.platform_id or identity.id
    return f"{identity.name}_{pid}_assignsubmission_file_"


def canvas_entry_with_raw_name(identity) -> str:       # noqa: ANN001 - a stand-in for entry_name
    """The name's characters as given: digits in a name become Canvas's user id."""
    from grader.batch.canvas_export import attachment_id, canvas_user_id

    name = identity.name.replace("/", "")
    return f"{name}_{canvas_user_id(identity)}_{attachment_id(identity)}_feedback.html"
