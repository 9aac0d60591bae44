"""``summary.html``: the class at a glance, for the instructor.

Per-check pass rates and mean points, the score distribution as an inline SVG histogram (the report
package's SVG helpers), and a table of students linking to each report and to each scenario run's
section in it (a small badge per run, red when the run failed), laid out to fit a 1024 px window.
Self-contained (no scripts, no external files), built from the per-student results only. Every
student-controlled value (ids, messages) reaches the page through the template (made visible by
`page_text`, then autoescaped); the plots are `Markup` built from numbers and escaped labels.
"""

from __future__ import annotations

from pathlib import Path
from urllib.parse import quote

from jinja2 import Environment

from grader.batch.exports import check_ids, class_max_score
from grader.batch.store import write_atomic
from grader.batch.stored import well_formed
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
    """`text` cut to at most `limit` characters at a word's end (inside a word as long as half of it), with
    "…" saying that more was cut."""
    if len(text) <= limit:
        return text
    cut = text[:limit - 1]
    head = cut.rsplit(" ", 1)[0] if " " in cut else cut
    if len(head) < limit // 2:  # one long word (a path): cut inside it rather than show almost nothing
        head = cut
    return head.rstrip(" ,;:") + "…"


def middle_cut(text: str, limit: int) -> str:
    """`text` of at most `limit` characters: a longer one keeps its start and its end (where ids that
    share a prefix differ) around "…"."""
    if len(text) <= limit:
        return text
    tail = (limit - 1) // 3
    return text[:limit - 1 - tail] + "…" + text[-tail:]


def graded_scores(results: dict[str, dict]) -> list[float]:
    """The scores of the graded students (the others have no meaningful score)."""
    return [float(r["score"]) for r in results.values()
            if r.get("status") == "graded" and isinstance(r.get("score"), (int, float))]


# The page is laid out for a 1024 px window and up (tests/batch/test_summary_browser.py): tables as wide as
# the window with fixed column widths, long words broken anywhere, a message cut short with its whole text
# one click away, each run's replay a small badge. A class-level section (a list of students, a table) is
# one <section> between the header and the checks; a students' column is one <col>, <th> and <td>.
_TEMPLATE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="{{ csp }}">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Week {{ week }} class summary</title>
<style>
*{box-sizing:border-box}body{font-family:system-ui,sans-serif;margin:1em 1.5em;color:#222;line-height:1.35}
h1{font-size:1.5em;margin:.2em 0 .4em}h2{font-size:1.2em;margin:1.2em 0 .4em}p,ul{overflow-wrap:anywhere}
table{border-collapse:collapse;margin:.5em 0;width:100%;table-layout:fixed}
td,th{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top;overflow-wrap:anywhere}
th{background:#f4f6f8}td.n,th.n{text-align:right}code{font-size:.9em}
svg.plot{display:block;max-width:100%;height:auto}
.bar{display:inline-block;height:10px;background:#3b7dd8;vertical-align:middle;margin-right:4px}
.graded{color:#176b2c}.invalid,.crashed,.timeout,.held{color:#a11}
col.student{width:12em}col.status{width:5.5em}col.score{width:7em}col.replays{width:30%}
col.kind{width:5.5em}col.max{width:3.5em}col.rate{width:8.5em}col.mean{width:4.5em}col.errors{width:5em}
.runs{display:inline-flex;flex-wrap:wrap;gap:2px;margin:0 6px 2px 0;vertical-align:top}
a.run{display:inline-block;min-width:1.6em;padding:0 3px;border-radius:3px;background:#e3edf9;color:#1f4fd1;
text-align:center;text-decoration:none;font-size:.8em;line-height:1.6}
a.run.failed{background:#fbe3e4;color:#a11;font-weight:600}a.run:hover{outline:1px solid currentColor}
details.message summary{cursor:pointer}details.message[open] summary{color:#555}
.legend{font-size:.9em;color:#444}
</style></head><body>
<header>
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
{% if similarity %}<p><a href="similarity.html">Similar code blocks</a>: pairs of students whose code
looks alike.</p>{% endif %}
{% if intake %}<div class="intake"><p>Read as {{ intake.layout }}.
{%- if intake.policy %} Late policy: {{ intake.policy }}.{% endif %}</p>
{% for title, names in intake.lists %}{% if names %}<p><strong>{{ title }} ({{ names|length }}):</strong>
{{ names[:200]|join(", ") }}{% if names|length > 200 %} and {{ names|length - 200 }} more{% endif %}</p>
{% endif %}{% endfor %}</div>{% endif %}
</header>
{% if changed %}<section id="changed"><h2>Scores changed by a regrade</h2>
<table><tr><th>student</th><th>graded again</th><th>before</th><th>now</th><th>why graded again</th></tr>
{% for c in changed %}<tr><td>{{ c.student }}</td>
<td>{{ "this run" if c.this_run else (c.at[:16]|replace("T", " ") or "earlier") }}</td>
<td class="n">{{ "%g"|format(c.before) if c.before is not none else "" }} {{ c.status_before }}</td>
<td class="n">{{ "%g"|format(c.after) if c.after is not none else "" }} {{ c.status_after }}</td>
<td>{{ c.reasons|join(", ") }}</td></tr>
{% endfor %}</table></section>{% endif %}
<section id="scores">
<h2>Score distribution (graded submissions)</h2>
{{ histogram }}
</section>
<section id="checks">
<h2>Checks</h2>
{{ pass_rates }}
<table><colgroup><col class="check"><col class="name"><col class="kind"><col class="max"><col class="rate">
<col class="mean"><col class="errors"></colgroup>
<tr><th>check</th><th>name</th><th>kind</th><th class="n">max</th><th>pass rate</th><th class="n">mean</th>
<th class="n">errors</th></tr>
{% for c in checks %}<tr><td><code>{{ c.id }}</code></td><td>{{ c.name }}</td><td>{{ c.kind }}</td>
<td class="n">{{ "%g"|format(c.max_points) }}</td>
<td><span class="bar" style="width:{{ (c.pass_rate * 60)|round|int }}px"></span>
{{- (c.pass_rate * 100)|round|int }}%</td>
<td class="n">{{ "%.2f"|format(c.mean_points) }}</td><td class="n">{{ c.errors }}</td></tr>
{% endfor %}</table>
</section>
<section id="students">
<h2>Students</h2>
{% if replay_groups %}<p class="legend">Replays: one badge per scenario run, red where it missed its goal,
collided or a check on it failed; in each row in this order: {{ replay_groups|join(", ") }}.
A badge's tooltip names its run and checks.</p>{% endif %}
<table><colgroup><col class="student"><col class="status"><col class="score"><col class="replays">
<col class="message"></colgroup>
<tr><th>student</th><th>status</th><th class="n">score</th><th>replays</th><th>message</th></tr>
{% for s in students %}<tr><td><a href="{{ s.href }}"{% if s.shown != s.id %} title="{{ s.id }}"{% endif %}>
{{- s.shown }}</a></td>
<td class="{{ s.status }}">{{ s.status }}</td>
<td class="n">{% if s.score is not none %}{{ "%g"|format(s.score) }}
{%- if max_score %} / {{ "%g"|format(max_score) }}{% endif %}{% endif %}
{%- if s.late %} (late: &minus;{{ "%g"|format(s.late) }}){% endif %}</td>
<td>{% for g in s.replays %}<span class="runs" title="{{ g.name }}">{% for r in g.runs %}<a class="run
{%- if r.failed %} failed{% endif %}" href="{{ r.href }}"
title="{{ g.name }} run {{ r.text }}: {{ r.title }}">{{ r.text }}</a>{% endfor %}</span>{% endfor %}</td>
<td>{% if s.full %}<details class="message"><summary>{{ s.message }}</summary>{{ s.full }}</details>
{%- else %}{{ s.message }}{% endif %}</td></tr>
{% endfor %}</table>
</section>
</body></html>
"""

_env = Environment(autoescape=True, finalize=page_text)
MESSAGE_SHOWN, MESSAGE_KEPT = 100, 4000   # characters of a message in its cell; behind "more" (details)
ID_SHOWN = 40           # characters of a student id in its cell (the whole id in its tooltip and their page)


def summary_context(results: dict[str, dict], stems: dict[str, str], meta: dict) -> dict:
    """What the page shows (the template's variables), from the per-student results and the run's meta.
    A result grader.batch.stored finds malformed is left out (the runner regrades it), never read."""
    results = {sid: r for sid, r in results.items() if well_formed(r)}
    max_score = class_max_score(results)
    graded = graded_scores(results)
    stats = check_stats(results)
    status_counts: dict[str, int] = {}
    for result in results.values():
        status_counts[str(result.get("status"))] = status_counts.get(str(result.get("status")), 0) + 1
    students = []
    groups: dict[str, None] = {}
    for sid, r in sorted(results.items()):
        message = " ".join(str(r.get("message") or "").split())
        replays = replay_links(r, quote(f"{stems[sid]}.html"))
        groups.update((g["name"], None) for g in replays)
        short = shortened(message, MESSAGE_SHOWN)
        students.append({"id": sid, "shown": middle_cut(sid, ID_SHOWN), "href": quote(f"{stems[sid]}.html"),
                         "status": r.get("status"),
                         "replays": replays,
                         "score": r.get("score") if isinstance(r.get("score"), (int, float)) else None,
                         "message": short,
                         "full": shortened(message, MESSAGE_KEPT) if short != message else "",
                         "late": _late_points(r)})
    return dict(
        csp=STATIC_PAGE_CSP, week=meta.get("week"), seed=meta.get("seed"), hidden=meta.get("hidden"),
        grader=meta.get("grader"), incomplete=meta.get("incomplete", 0),
        not_graded=meta.get("not_graded") or [], results=results,
        status_counts=dict(sorted(status_counts.items())),
        mean=sum(graded) / len(graded) if graded else None, max_score=max_score,
        histogram=histogram_svg(graded, max_score or 1.0, title="Scores of graded submissions"),
        pass_rates=pass_rate_svg([(c["id"], c["pass_rate"]) for c in stats]) if stats else "",
        checks=stats, students=students, replay_groups=list(groups), intake=_intake(meta),
        similarity=meta.get("similarity_page"), changed=meta.get("changed") or [])


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


def summary_html(results: dict[str, dict], stems: dict[str, str], meta: dict) -> str:
    """The page's HTML; ``meta`` gives week, seed, hidden, grader and ``incomplete`` (students not done)."""
    return _env.from_string(_TEMPLATE).render(**summary_context(results, stems, meta))


def write_summary(out: Path, results: dict[str, dict], stems: dict[str, str], meta: dict) -> None:
    """Write ``out/summary.html``."""
    page = out / "similarity.html"     # grade similarity's, or --similarity's, written before this page
    meta = {**meta, "similarity_page": page.is_file() and not page.is_symlink()}
    write_atomic(out / "summary.html", summary_html(results, stems, meta))
