"""A student's ``<id>.html`` when the grader produced no report of its own.

Every student gets a page to open: for ``invalid``, ``timeout`` or ``crashed`` it says what happened and
what to do; for a graded result without a grader report (the report package missing) it lists the checks.
Everything shown comes from the student's result and id, so it reaches the page only through the template
(made visible by `page_text`, then autoescaped), under a policy that lets no script run.
"""

from __future__ import annotations

from jinja2 import Environment

from grader.report.html import STATIC_PAGE_CSP, page_text

_ADVICE = {
    "invalid": "The submission could not be graded as it is. Fix what the message says and submit again.",
    "held": "Your submission is being sorted out by your instructor (a question about the files as the "
            "course platform handed them over, not about your work). You need not do anything; this page "
            "will show your grade once it is sorted out.",
    "timeout": "Grading did not finish within the time budget. Your instructor will look into it.",
    "crashed": "The grader itself failed on this submission. Your instructor will look into it.",
}

_TEMPLATE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="{{ csp }}">
<title>{{ student }}: week {{ week }}</title>
<style>body{font-family:system-ui,sans-serif;margin:2em;color:#222}table{border-collapse:collapse}
td,th{border:1px solid #ccc;padding:4px 8px;text-align:left;vertical-align:top}
td.msg{white-space:pre-wrap;overflow-wrap:anywhere}</style></head><body>
<h1>Week {{ week }}: {{ student }}</h1>
<p>Status: <strong>{{ status }}</strong></p>
{% if status == "graded" %}<p>Score: {{ score }} / {{ max_score }}</p>{% endif %}
{% if message %}<p class="msg">{{ message }}</p>{% endif %}
{% if advice %}<p>{{ advice }}</p>{% endif %}
{% if checks %}<table><tr><th>check</th><th>name</th><th>status</th><th>points</th><th>message</th></tr>
{% for c in checks %}<tr><td>{{ c.id }}</td><td>{{ c.name }}</td><td>{{ c.status }}</td>
<td>{{ c.points }} / {{ c.max_points }}</td><td class="msg">{{ c.message }}</td></tr>
{% endfor %}</table>{% endif %}
<p>Graded with grader <code>{{ grader }}</code>, seed <code>{{ seed }}</code>.</p>
</body></html>
"""

_env = Environment(autoescape=True, finalize=page_text)


def fallback_page(student_id: str, result: dict) -> str:
    """A small self-contained HTML page for a result that has no grader report."""
    status = str(result.get("status", "crashed"))
    checks = [{k: str(c.get(k, "")) for k in ("id", "name", "status", "points", "max_points", "message")}
              for c in result.get("checks") or [] if isinstance(c, dict)]
    return _env.from_string(_TEMPLATE).render(
        csp=STATIC_PAGE_CSP, student=student_id, week=str(result.get("week")), status=status,
        score=str(result.get("score")), max_score=str(result.get("max_score")),
        # a held student's message is the instructor's (it may name the export's other entries)
        message="" if status == "held" else str(result.get("message") or ""), advice=_ADVICE.get(status, ""),
        checks=checks, grader=str(result.get("grader_version") or ""), seed=str(result.get("seed")))
