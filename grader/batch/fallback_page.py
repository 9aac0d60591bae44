"""A student's ``<id>.html`` when the grader produced no report of its own.

Every student gets a page to open: for ``invalid``, ``timeout`` or ``crashed`` it says what happened and
what to do; for a graded result without a grader report (the report package missing) it lists the checks.
"""

from __future__ import annotations

from html import escape

_ADVICE = {
    "invalid": "The submission could not be graded as it is. Fix what the message says and submit again.",
    "timeout": "Grading did not finish within the time budget. Your instructor will look into it.",
    "crashed": "The grader itself failed on this submission. Your instructor will look into it.",
}


def _checks_table(checks: list) -> str:
    rows = "".join(
        f"<tr><td>{escape(str(c.get('id', '')))}</td><td>{escape(str(c.get('name', '')))}</td>"
        f"<td>{escape(str(c.get('status', '')))}</td>"
        f"<td>{escape(str(c.get('points', '')))} / {escape(str(c.get('max_points', '')))}</td>"
        f"<td>{escape(str(c.get('message', '')))}</td></tr>"
        for c in checks if isinstance(c, dict))
    return ("<table border=1 cellpadding=4 style='border-collapse:collapse'><tr><th>check</th><th>name</th>"
            f"<th>status</th><th>points</th><th>message</th></tr>{rows}</table>") if rows else ""


def fallback_page(student_id: str, result: dict) -> str:
    """A small self-contained HTML page for a result that has no grader report."""
    status = str(result.get("status", "crashed"))
    week = escape(str(result.get("week")))
    score = (f"<p>Score: {escape(str(result.get('score')))} / {escape(str(result.get('max_score')))}</p>"
             if status == "graded" else "")
    return (f'<!doctype html><html lang="en"><head><meta charset="utf-8"><title>{escape(student_id)}: '
            f'week {week}</title></head><body style="font-family:system-ui,sans-serif">'
            f'<h1>Week {week}: {escape(student_id)}</h1>'
            f'<p>Status: <strong>{escape(status)}</strong></p>{score}'
            f'<p>{escape(str(result.get("message") or ""))}</p>'
            f'<p>{escape(_ADVICE.get(status, ""))}</p>'
            f'{_checks_table(result.get("checks") or [])}</body></html>\n')
