"""A student's ``<id>.html`` when the grader produced no report (invalid, timeout, crashed).

Every student gets a page to open, saying what happened and what to do, even when grading never ran.
"""

from __future__ import annotations

from html import escape

_ADVICE = {
    "invalid": "The submission could not be graded as it is. Fix what the message says and submit again.",
    "timeout": "Grading did not finish within the time budget. Your instructor will look into it.",
    "crashed": "The grader itself failed on this submission. Your instructor will look into it.",
}


def fallback_page(student_id: str, result: dict) -> str:
    """A small self-contained HTML page for a result that has no grader report."""
    status = str(result.get("status", "crashed"))
    return (f'<!doctype html><html lang="en"><head><meta charset="utf-8"><title>{escape(student_id)}: '
            f'week {escape(str(result.get("week")))}</title></head>'
            f'<body style="font-family:system-ui,sans-serif">'
            f'<h1>Week {escape(str(result.get("week")))}: {escape(student_id)}</h1>'
            f'<p>Status: <strong>{escape(status)}</strong></p>'
            f'<p>{escape(str(result.get("message") or ""))}</p>'
            f'<p>{escape(_ADVICE.get(status, ""))}</p></body></html>\n')
