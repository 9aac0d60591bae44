"""``similarity.html``, ``similarity.json`` and the printed top list: the pairs worth a person's look.

The page ranks the pairs whose score reaches the threshold and shows each pair's compared blocks side by
side, the shared passages marked. It is self-contained (no scripts, no external files, the same
Content-Security-Policy as the batch summary) and fits a 1024 px window: code wraps inside its own box.
Every student-controlled value (ids, code, notes) reaches the page through the autoescaped template,
made visible by ``page_text`` first; ids are cut to MAX_ID_SHOWN characters, the names students have on
the platform or the roster (grader.batch.identity) to MAX_NAME_SHOWN.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TextIO

from jinja2 import Environment

from grader.report.html import STATIC_PAGE_CSP, page_text
from grader.similarity.compare import Pair
from grader.similarity.submitted import StudentCode
from grader.untrusted import printable

MAX_ID_SHOWN = 64
MAX_NAME_SHOWN = 60
MAX_SIDE_BY_SIDE = 100     # pairs shown with their code; the others above the threshold are listed only
MAX_LISTED = 2000          # pairs listed on the page and in the JSON

_TEMPLATE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="{{ csp }}">
<meta name="viewport" content="width=device-width">
<title>Week {{ week }}: similar code blocks</title>
<style>
body{font-family:system-ui,sans-serif;margin:1em;color:#222;max-width:100%;overflow-wrap:anywhere}
table{border-collapse:collapse;margin:1em 0;width:100%;table-layout:fixed}
td,th{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top;overflow-wrap:anywhere}
th.rank{width:3em}th.score{width:5em}th.who{width:20%}td.n{text-align:right}
.pair{border-top:2px solid #888;margin-top:2em}
.sides{display:grid;grid-template-columns:minmax(0,1fr) minmax(0,1fr);gap:1em}
.side{min-width:0}
pre{white-space:pre-wrap;overflow-wrap:anywhere;max-height:30em;overflow:auto;background:#f6f6f6;
border:1px solid #ddd;padding:4px;margin:0 0 .8em 0;font-size:13px}
mark{background:#ffd76a}h4{margin:.6em 0 .2em 0;font-size:14px}.note{color:#555}
</style></head><body>
<h1>Week {{ week }}: similar code blocks</h1>
<p>Read from {{ source }}.</p>
<p>{{ compared }} submissions compared ({{ pair_count }} pairs);
<strong>{{ flagged|length }}</strong> {{ "pair scores" if flagged|length == 1 else "pairs score" }}
{{ "%d"|format(threshold * 100) }} % or more.
Only the students' code blocks are compared, with the handout's own lines taken out ({{ handout }});
names, comments and layout do not count. A pair's score is the share of the smaller side's
fingerprints (runs of {{ k }} tokens, winnowed over windows of {{ window }}) that the other side has too;
passages found in more than {{ common }} submissions count for nobody.</p>
<p class="note">A high score flags a pair for a person to read; it is not a finding of copying. Short
blocks written from the same formulas look alike, and two students may share a source they were allowed.</p>
{% if flagged %}
<table><tr><th class="rank">#</th><th class="who">student</th><th class="who">student</th>
<th class="score">score</th><th>blocks that match (shared fingerprints)</th></tr>
{% for p in flagged %}<tr><td class="n">{% if p.shown %}<a href="#pair-{{ p.rank }}">{{ p.rank }}</a>
{%- else %}{{ p.rank }}{% endif %}</td><td>{{ p.a }}</td><td>{{ p.b }}</td>
<td class="n">{{ "%d"|format(p.score * 100) }} %</td>
<td>{% for m in p.blocks[:6] %}{{ m.a }}{% if m.b != m.a %} / {{ m.b }}{% endif %} ({{ m.shared }})
{%- if not loop.last %}; {% endif %}{% endfor %}{% if p.blocks|length > 6 %}; …{% endif %}</td></tr>
{% endfor %}</table>
{% if flagged|length > shown %}<p>The first {{ shown }} pairs are shown below; similarity.json lists
them all.</p>{% endif %}
{% else %}<p>No pair reaches the threshold.</p>{% endif %}
{% if best_below %}<p>Highest scores below the threshold:
{% for p in best_below %}{{ p.a }} and {{ p.b }} {{ "%d"|format(p.score * 100) }} %
{%- if not loop.last %}; {% endif %}{% endfor %}.</p>{% endif %}
{% if not_compared %}<h2>Not compared</h2><ul>
{% for s in not_compared %}<li>{{ s.id }}: {{ s.why }}</li>{% endfor %}</ul>{% endif %}
{% if unplaced %}<p>{{ unplaced_count }} {{ "entry" if unplaced_count == 1 else "entries" }} of the
download could not be placed with any student (not compared): {{ unplaced|join("; ") }}
{%- if unplaced_count > unplaced|length %}; …{% endif %}.</p>{% endif %}
{% if notes %}<h2>Compared in part</h2><ul>
{% for s in notes %}<li>{{ s.id }}: {{ s.notes|join("; ") }}</li>{% endfor %}</ul>{% endif %}
{% for p in flagged[:shown] %}
<section class="pair" id="pair-{{ p.rank }}">
<h2>{{ p.rank }}. {{ p.a }} and {{ p.b }}: {{ "%d"|format(p.score * 100) }} %</h2>
<p>{{ p.shared }} fingerprints shared, of {{ p.sizes[0] }} and {{ p.sizes[1] }}.</p>
<div class="sides">{% for side in p.sides %}<div class="side"><h3>{{ side.id }}</h3>
{% for b in side.blocks %}<h4>{{ b.label }}</h4><pre>{% for text, marked in b.parts %}
{%- if marked %}<mark>{{ text }}</mark>{% else %}{{ text }}{% endif %}{% endfor %}</pre>
{% endfor %}{% if side.others %}<p class="note">No match in: {{ side.others|join(", ") }}.</p>{% endif %}
</div>{% endfor %}</div>
</section>
{% endfor %}
</body></html>
"""

_env = Environment(autoescape=True, finalize=page_text)


def shown_id(sid: str) -> str:
    """A student id as the page and the terminal show it: visible characters, at most MAX_ID_SHOWN."""
    text = printable(sid, multiline=False)
    return text if len(text) <= MAX_ID_SHOWN else text[:MAX_ID_SHOWN - 1] + "…"


def shown_student(sid: str, name: str = "") -> str:
    """``101 (Doe, Jane)``: the id, and the name the platform or the roster gives, both made visible and
    cut to length (the page escapes them)."""
    if not name:
        return shown_id(sid)
    text = printable(" ".join(name.split()), multiline=False)
    text = text if len(text) <= MAX_NAME_SHOWN else text[:MAX_NAME_SHOWN - 1] + "…"
    return f"{shown_id(sid)} ({text})"


def _parts(text: str, spans: list[tuple[int, int]]) -> list[tuple[str, bool]]:
    out: list[tuple[str, bool]] = []
    at = 0
    for start, end in spans:
        if start > at:
            out.append((text[at:start], False))
        out.append((text[start:end], True))
        at = end
    if at < len(text):
        out.append((text[at:], False))
    return out


def _side(code: StudentCode, spans: dict[int, list[tuple[int, int]]]) -> dict:
    blocks = [{"label": b.label, "parts": _parts(b.text, spans[i])}
              for i, b in enumerate(code.blocks) if i in spans]
    others = [b.label for i, b in enumerate(code.blocks) if i not in spans and b.compared.strip()]
    return {"id": shown_student(code.id, code.name), "blocks": blocks, "others": others}


def pair_json(pair: Pair, rank: int) -> dict:
    """One pair as plain data: the ids exactly as the batch has them, the names as their Identity."""
    return {"rank": rank, "a": pair.a.id, "b": pair.b.id, "a_name": pair.a.name, "b_name": pair.b.name,
            "score": pair.score, "shared": pair.shared, "fingerprints": list(pair.sizes),
            "blocks": pair.blocks}


def report_json(pairs: Sequence[Pair], codes: Sequence[StudentCode], not_compared: dict[str, str],
                meta: dict, names: dict[str, str] | None = None) -> dict:
    """``similarity.json``: the settings, every pair at or above the threshold (best first, at most
    MAX_LISTED), who was not compared, with why, and everyone's name (``names``: {id: name})."""
    flagged = [p for p in pairs if p.score >= meta["threshold"]]
    return {"format": "simiam-similarity/1", **meta, "compared": len(codes),
            "pairs": [pair_json(p, r) for r, p in enumerate(flagged[:MAX_LISTED], start=1)],
            "pairs_above_threshold": len(flagged),
            "notes": {c.id: c.notes for c in codes if c.notes},
            "not_compared": dict(sorted(not_compared.items())), "names": dict(sorted((names or {}).items()))}


def similarity_html(pairs: Sequence[Pair], codes: Sequence[StudentCode], not_compared: dict[str, str],
                    meta: dict, names: dict[str, str] | None = None) -> str:
    """The page (``meta``: week, threshold, k, window, common, handout, source, unplaced_count;
    ``names``: {id: name} of those not compared)."""
    names = names or {}
    flagged = []
    above = [p for p in pairs if p.score >= meta["threshold"]]
    for rank, p in enumerate(above[:MAX_LISTED], start=1):
        view = {"rank": rank, "a": shown_student(p.a.id, p.a.name), "b": shown_student(p.b.id, p.b.name),
                "score": p.score, "shared": p.shared, "sizes": p.sizes, "blocks": p.blocks,
                "shown": rank <= MAX_SIDE_BY_SIDE}
        if view["shown"]:
            view["sides"] = [_side(p.a, p.spans[0]), _side(p.b, p.spans[1])]
        flagged.append(view)
    below = [{"a": shown_student(p.a.id, p.a.name), "b": shown_student(p.b.id, p.b.name), "score": p.score}
             for p in pairs if p.score < meta["threshold"]][:5]
    n = len(codes)
    return _env.from_string(_TEMPLATE).render(
        csp=STATIC_PAGE_CSP, week=meta["week"], threshold=meta["threshold"], k=meta["k"],
        window=meta["window"], common=meta["common"], handout=meta["handout"], compared=n,
        pair_count=n * (n - 1) // 2, flagged=flagged, shown=MAX_SIDE_BY_SIDE, best_below=below,
        source=meta.get("source") or "a class folder", unplaced=meta.get("unplaced") or [],
        unplaced_count=meta.get("unplaced_count") or 0,
        not_compared=[{"id": shown_student(sid, names.get(sid, "")), "why": why}
                      for sid, why in sorted(not_compared.items())],
        notes=[{"id": shown_student(c.id, c.name), "notes": c.notes[:5]}
               for c in sorted(codes, key=lambda c: c.id) if c.notes][:MAX_LISTED])


def print_top(pairs: Sequence[Pair], threshold: float, stream: TextIO, top: int = 10) -> None:
    """The best pairs at or above the threshold, one line each, for the terminal."""
    above = [p for p in pairs if p.score >= threshold]
    said = "1 pair scores" if len(above) == 1 else f"{len(above)} pairs score"
    print(f"{said} {threshold:.0%} or more", file=stream)
    for rank, p in enumerate(above[:top], start=1):
        labels = list(dict.fromkeys(m["a"] for m in p.blocks))     # most shared first, each once
        blocks = ", ".join(labels[:3]) + (", ..." if len(labels) > 3 else "")
        print(f"  {rank:>3}. {p.score:>4.0%}  {shown_student(p.a.id, p.a.name)}  "
              f"{shown_student(p.b.id, p.b.name)}  ({blocks})", file=stream)
    if len(above) > top:
        print(f"  ... and {len(above) - top} more", file=stream)
