"""``summary.html``: the class at a glance, for the instructor.

Per-check pass rates and mean points, the score distribution as an inline SVG histogram (the report
package's SVG helpers), and a table of students linking to each report and straight to each scenario
run's replay in it (red when the check that ran it failed). Self-contained (no scripts, no
external files), built from the per-student results only. Every student-controlled value (ids, messages)
reaches the page through the template (made visible by `page_text`, then autoescaped); the plots are
`Markup` built from numbers and escaped labels.
"""

from __future__ import annotations

from pathlib import Path
from urllib.parse import quote

from jinja2 import Environment

from grader.batch.exports import check_ids, class_max_score
from grader.batch.store import write_atomic
from grader.report.html import STATIC_PAGE_CSP, page_text, run_anchor
from grader.report.svg import histogram_svg, pass_rate_svg


def check_stats(results: dict[str, dict]) -> list[dict]:
    """For each check: how many graded students ran it, the pass rate and the mean points."""
    stats = []
    for cid in check_ids(results):
        runs = [c for r in results.values() if r.get("status") == "graded"
                for c in r.get("checks") or [] if isinstance(c, dict) and c.get("id") == cid]
        if not runs:
            continue
        points = [float(c.get("points") or 0.0) for c in runs]
        passed = sum(c.get("status") == "passed" for c in runs)
        stats.append({"id": cid, "name": runs[0].get("name") or cid, "kind": runs[0].get("kind") or "",
                      "max_points": float(runs[0].get("max_points") or 0.0), "n": len(runs),
                      "pass_rate": passed / len(runs), "mean_points": sum(points) / len(points),
                      "errors": sum(c.get("status") in ("error", "timeout") for c in runs)})
    return stats


def replay_links(result: dict, page: str) -> list[dict]:
    """Links to the replay sections (``page#run-...``) of the scenario runs a student's report embeds,
    each run once, grouped by the check that kept it, named by its part and check so that week 5's
    blending and switching runs stay apart: ``[{"name": "blending.reach_goal", "runs": [{"href",
    "text": "1", "title", "failed"}, ...]}]``. A run is ``failed`` (red) by its own record when a check
    kept one (not reached, collided, a problem): a run that reached its goal is not red because another
    run of its check missed; a run no check recorded on its own is failed when a check measured on it
    failed."""
    runs: dict[str, dict] = {}
    groups: dict[str, list[dict]] = {}
    for check in result.get("checks") or []:
        details = check.get("details") if isinstance(check, dict) else None
        keys = details.get("traces") if isinstance(details, dict) else None
        records = details.get("runs") if isinstance(details, dict) else None
        keys = keys if isinstance(keys, list) else []
        records = records if isinstance(records, list) and len(records) == len(keys) else [None] * len(keys)
        for key, record in zip(keys, records, strict=True):
            if not isinstance(key, str):
                continue
            if key not in runs:
                name, _, number = key.partition("#")
                runs[key] = {"href": f"{page}#{run_anchor(key)}", "text": number or "1", "checks": [],
                             "own": None, "failed": False}
                groups.setdefault(name.split(".", 1)[-1], []).append(runs[key])
            runs[key]["checks"].append(f"{check.get('id')}: {check.get('status')}")
            runs[key]["failed"] = runs[key]["failed"] or check.get("status") != "passed"
            own = _run_failed(record)
            if own is not None:
                runs[key]["own"] = own or bool(runs[key]["own"])
    for run in runs.values():
        run["title"] = "; ".join(run.pop("checks"))
        own = run.pop("own")
        if own is not None:
            run["failed"] = own
    return [{"name": name, "runs": group} for name, group in groups.items()]


def _run_failed(record: object) -> bool | None:
    """What a check's record of one run says of it: True (missed its goal, collided or stopped with a
    problem), False (reached it cleanly), None (the record says neither)."""
    if not isinstance(record, dict) or not any(k in record for k in ("reached", "collided", "problem")):
        return None
    return record.get("reached") is False or record.get("collided") is True or bool(record.get("problem"))


def shortened(text: str, limit: int) -> str:
    """`text` cut to at most `limit` characters at a word's end, with "…" saying that more was cut."""
    if len(text) <= limit:
        return text
    cut = text[:limit - 1]
    head = cut.rsplit(" ", 1)[0] if " " in cut else cut
    return head.rstrip(" ,;:") + "…"


def graded_scores(results: dict[str, dict]) -> list[float]:
    """The scores of the graded students (the others have no meaningful score)."""
    return [float(r["score"]) for r in results.values()
            if r.get("status") == "graded" and isinstance(r.get("score"), (int, float))]


_TEMPLATE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="{{ csp }}"><title>Week {{ week }} class summary</title>
<style>
body{font-family:system-ui,sans-serif;margin:2em;color:#222}table{border-collapse:collapse;margin:1em 0}
td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}td.n{text-align:right;white-space:nowrap}
.bar{display:inline-block;height:10px;background:#3b7dd8}.graded{color:#176b2c}
.invalid,.crashed,.timeout,a.failed{color:#a11}td.replays{white-space:nowrap}
</style></head><body>
<h1>Week {{ week }}: class summary</h1>
<p>{{ results|length }} students:
{% for s, n in status_counts.items() %}{{ n }} {{ s }}{% if not loop.last %}, {% endif %}{% endfor %}.
Seed {{ seed }}; grader {{ grader }}; hidden checks {{ "included" if hidden else "not run" }}.
{% if mean is not none %}Mean score {{ "%.2f"|format(mean) }}
{%- if max_score %} / {{ "%g"|format(max_score) }}{% endif %}.{% endif %}</p>
{% if incomplete %}<p><strong>Incomplete:</strong> {{ incomplete }} submissions not graded yet;
rerun the same command to finish.</p>
{% if not_graded %}<p>Not graded yet: {{ not_graded[:200]|join(", ") }}
{%- if not_graded|length > 200 %} and {{ not_graded|length - 200 }} more{% endif %}.</p>{% endif %}
{% endif %}
{% if intake %}<div class="intake"><p>Read as {{ intake.layout }}.
{%- if intake.policy %} Late policy: {{ intake.policy }}.{% endif %}</p>
{% for title, names in intake.lists %}{% if names %}<p><strong>{{ title }} ({{ names|length }}):</strong>
{{ names[:200]|join(", ") }}{% if names|length > 200 %} and {{ names|length - 200 }} more{% endif %}</p>
{% endif %}{% endfor %}</div>{% endif %}
{% if changed %}<h2>Changed since last grading</h2>
<table><tr><th>student</th><th>before</th><th>now</th><th>why graded again</th></tr>
{% for c in changed %}<tr><td>{{ c.student }}</td>
<td class="n">{{ "%g"|format(c.before) if c.before is not none else "" }} {{ c.status_before }}</td>
<td class="n">{{ "%g"|format(c.after) if c.after is not none else "" }} {{ c.status_after }}</td>
<td>{{ c.reasons|join(", ") }}</td></tr>
{% endfor %}</table>{% endif %}
<h2>Score distribution (graded submissions)</h2>
{{ histogram }}
<h2>Checks</h2>
{{ pass_rates }}
<table><tr><th>check</th><th>name</th><th>kind</th><th>max</th><th>pass rate</th><th>mean points</th>
<th>errors</th></tr>
{% for c in checks %}<tr><td><code>{{ c.id }}</code></td><td>{{ c.name }}</td><td>{{ c.kind }}</td>
<td class="n">{{ "%g"|format(c.max_points) }}</td>
<td style="white-space:nowrap"><span class="bar" style="width:{{ (c.pass_rate * 80)|round|int }}px"></span>
{{ (c.pass_rate * 100)|round|int }}%</td>
<td class="n">{{ "%.2f"|format(c.mean_points) }}</td><td class="n">{{ c.errors }}</td></tr>
{% endfor %}</table>
<h2>Students</h2>
<table><tr><th>student</th><th>status</th><th>score</th><th>replays</th><th>message</th></tr>
{% for s in students %}<tr><td><a href="{{ s.href }}">{{ s.id }}</a></td>
<td class="{{ s.status }}">{{ s.status }}</td>
<td class="n">{% if s.score is not none %}{{ "%g"|format(s.score) }}
{%- if max_score %} / {{ "%g"|format(max_score) }}{% endif %}{% endif %}
{%- if s.late %} (late: &minus;{{ "%g"|format(s.late) }}){% endif %}</td>
<td class="replays">{% for g in s.replays %}{{ g.name }}{% for r in g.runs %} <a href="{{ r.href }}"
title="{{ r.title }}"{% if r.failed %} class="failed"{% endif %}>{{ r.text }}</a>{% endfor %}
{%- if not loop.last %} · {% endif %}{% endfor %}</td>
<td>{{ s.message }}</td></tr>
{% endfor %}</table>
</body></html>
"""

_env = Environment(autoescape=True, finalize=page_text)


def summary_html(results: dict[str, dict], stems: dict[str, str], meta: dict) -> str:
    """The page's HTML; ``meta`` gives week, seed, hidden, grader and ``incomplete`` (students not done)."""
    max_score = class_max_score(results)
    graded = graded_scores(results)
    stats = check_stats(results)
    status_counts: dict[str, int] = {}
    for result in results.values():
        status_counts[str(result.get("status"))] = status_counts.get(str(result.get("status")), 0) + 1
    students = [{"id": sid, "href": quote(f"{stems[sid]}.html"), "status": r.get("status"),
                 "replays": replay_links(r, quote(f"{stems[sid]}.html")),
                 "score": r.get("score") if isinstance(r.get("score"), (int, float)) else None,
                 "message": shortened(" ".join(str(r.get("message") or "").split()), 300),
                 "late": _late_points(r)}
                for sid, r in sorted(results.items())]
    return _env.from_string(_TEMPLATE).render(
        csp=STATIC_PAGE_CSP, week=meta.get("week"), seed=meta.get("seed"), hidden=meta.get("hidden"),
        grader=meta.get("grader"), incomplete=meta.get("incomplete", 0),
        not_graded=meta.get("not_graded") or [], results=results,
        status_counts=dict(sorted(status_counts.items())),
        mean=sum(graded) / len(graded) if graded else None, max_score=max_score,
        histogram=histogram_svg(graded, max_score or 1.0, title="Scores of graded submissions"),
        pass_rates=pass_rate_svg([(c["id"], c["pass_rate"]) for c in stats]) if stats else "",
        checks=stats, students=students, intake=_intake(meta),
        changed=meta.get("changed") or [])


def _late_points(result: dict) -> float | None:
    late = result.get("late")
    points = late.get("penalty_points") if isinstance(late, dict) else None
    if isinstance(points, (int, float)) and not isinstance(points, bool) and points > 0:
        return float(points)
    return None


def _intake(meta: dict) -> dict | None:
    """What the instructor must hear about the intake (grader/batch/intake.py), None for a plain run."""
    if "layout_text" not in meta:
        return None
    notes = meta.get("intake") or {}
    reasons = meta.get("held_reasons") or {}
    return {"layout": meta["layout_text"], "policy": notes.get("late_policy_text") or "",
            "lists": [("Held: yours to sort out, not graded", [f"{k}: {v}" for k, v in reasons.items()]),
                      ("On the roster, no submission", meta.get("missing") or []),
                      ("Not on the roster (graded)", notes.get("not_on_roster") or []),
                      ("Not placed (not graded)", notes.get("unplaced") or []),
                      ("Marked late by Canvas, no submission time: give --times",
                       notes.get("late_without_time") or []),
                      ("Notes", notes.get("notes") or [])]}


def write_summary(out: Path, results: dict[str, dict], stems: dict[str, str], meta: dict) -> None:
    """Write ``out/summary.html``."""
    write_atomic(out / "summary.html", summary_html(results, stems, meta))
