"""The class summary's template before it was laid out for a 1024 px window (kept as the wrong version the
browser test must catch): its replays column never wrapped (~580 px for week 5), its messages ran to 300
characters, and at 1024 px the message column lay outside the window."""

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
{%- if max_score %} / {{ "%g"|format(max_score) }}{% endif %}{% endif %}</td>
<td class="replays">{% for g in s.replays %}{{ g.name }}{% for r in g.runs %} <a href="{{ r.href }}"
title="{{ r.title }}"{% if r.failed %} class="failed"{% endif %}>{{ r.text }}</a>{% endfor %}
{%- if not loop.last %} · {% endif %}{% endfor %}</td>
<td>{{ s.message }}</td></tr>
{% endfor %}</table>
</body></html>
"""
