"""Plots of a trace's declared debug signals and of its states, for the report: by name, from the trace's
own `signals` header, knowing no signal in advance (simiam.signals declares them; a trace says which it
recorded and of what kind).

A check asks for them in `Check.plots` (carried in its result's `plots`):
- `"states"`: which controller ran when (a band per state run), with a row per label and event signal;
- `"signals:d_prog,switches"`: those signals over time (numbers and counts as lines, an event as 0/1, a
  vector as its x and y).
Every label in these pictures is escaped; state names are the student's and are shown, never obeyed.
"""

from __future__ import annotations

from collections.abc import Sequence
from html import escape
from typing import Any

from markupsafe import Markup

from grader.report.svg import BLUE, GREEN, ORANGE, RED, Chart, Series, _finite, _n
from grader.untrusted import printable
from simiam.signals import COEFFICIENTS, WEEKS_1_TO_4, declared, from_headers, headers
from simiam.viewer.state_colours import state_color  # the replay's colours too

_SERIES = (BLUE, RED, GREEN, ORANGE, "#7a3db8", "#0f8b8d")
_ROW, _LEFT, _NAMES = 18, 96, 12  # px per timeline row, least px for the row labels, names in the legend
_CHAR = 7.0  # px per character of an 11 px label, generously (underscores and capitals are wide)
_ROW_LABEL = 24  # characters of a row's label shown


def declared_signals(trace: dict) -> list[dict]:
    """The trace's signal header (name, kind, unit, size); a trace without one recorded weeks 1-4's five.
    A malformed header gives no signals (the report still shows everything else)."""
    raw = trace.get("signals")
    try:
        if raw is None:
            n_ir = len((trace.get("robot") or {}).get("ir_mounts") or []) or 5
            return headers(declared(WEEKS_1_TO_4), n_ir)
        return from_headers(raw)
    except ValueError:
        return []


def signals_svg(trace: dict, names: Sequence[str], title: str | None = None) -> Markup | None:
    """The named signals over time, one chart per unit (a count never shares an axis with metres), or None
    if the trace declares none of them with a value."""
    found = {s["name"]: s for s in declared_signals(trace)}
    steps = trace.get("steps") or {}
    ts = list(steps.get("t") or [])
    by_unit: dict[str, list[Series]] = {}
    for name in names:
        sig = found.get(name)
        values = steps.get(name)
        if sig is None or not isinstance(values, list) or not any(v is not None for v in values):
            continue
        unit = "count" if sig["kind"] == "count" else "" if sig["kind"] == "flag" else sig.get("unit") or ""
        series = by_unit.setdefault(unit, [])
        colour = _SERIES[len(series) % len(_SERIES)]
        if sig["kind"] in ("scalar", "count"):
            series.append(Series(name, ts, _finite_or_none(values), colour))
        elif sig["kind"] == "flag":
            series.append(Series(name, ts, [None if v is None else float(v is True) for v in values], colour))
        elif sig["kind"] == "vector2":
            pair = (("1", 0), ("2", 1)) if unit == COEFFICIENTS else (("x", 0), ("y", 1))  # sigma: no x, y
            for axis, k in pair:
                ys = _finite_or_none([v[k] if isinstance(v, list) and len(v) == 2 else None for v in values])
                series.append(Series(f"{name} {axis}", ts, ys, _SERIES[len(series) % len(_SERIES)],
                                     dash="" if k == 0 else "6 4"))
        # labels and points have no line: "states" shows labels; the replay draws points
    charts = []
    for unit, series in by_unit.items():
        if not series:
            continue
        shown = title or ", ".join(dict.fromkeys(s.label.split()[0] for s in series))
        charts.append(Chart(series, title=shown + (f" ({unit})" if unit else ""), x_label="t (s)").render())
    return Markup("").join(charts) if charts else None


def _finite_or_none(values: list) -> list:
    """Each value that is a finite number, None for the rest (a float, nearly every value, checked inline)."""
    return [v if (v - v == 0.0 if type(v) is float else _finite(v)) else None for v in values]


def _runs(values: list, n: int) -> list[tuple[int, int, str]]:
    """(first row, last row, text) of each run of equal non-empty text."""
    runs: list[tuple[int, int, str]] = []
    for k in range(n):
        v = values[k] if k < len(values) else None
        text = v if isinstance(v, str) else ""
        if runs and runs[-1][2] == text and runs[-1][1] == k - 1:
            runs[-1] = (runs[-1][0], k, text)
        else:
            runs.append((k, k, text))
    return [r for r in runs if r[2]]


def states_svg(trace: dict, width: int = 460) -> Markup | None:
    """Which controller ran when: a band per state run, then a row per label signal (its value's band)
    and per event signal (marked where true). None for a trace without states."""
    steps = trace.get("steps") or {}
    ts = [t for t in steps.get("t") or [] if _finite(t)]
    n = len(ts)
    if n < 2:
        return None
    rows: list[tuple[str, Any]] = [("state", _runs(list(steps.get("state") or []), n))]
    for sig in declared_signals(trace):
        values = steps.get(sig["name"])
        if isinstance(values, list) and any(v is not None for v in values):
            if sig["kind"] == "label":
                rows.append((sig["name"], _runs(values, n)))
            elif sig["kind"] == "flag":
                rows.append((sig["name"], [k for k in range(min(n, len(values))) if values[k] is True]))
    if not rows[0][1] and len(rows) == 1:
        return None
    t0, t1 = ts[0], max(ts[-1], ts[0] + 1e-9)
    mr, mt = 10, 22
    # the row labels are right-aligned against the bands: the margin fits the longest, so that no label
    # ("obstacle_cleared") runs off the picture's left edge
    left = max(_LEFT, 12 + _CHAR * max(len(printable(label)[:_ROW_LABEL]) for label, _ in rows))
    legend_y = mt + _ROW * len(rows) + 18
    named = {text: None for _, marks in rows for m in marks if isinstance(m, tuple) for text in (m[2],)}
    legend = _legend_rows(list(named)[:_NAMES], width)
    height = legend_y + 20 * max(1, len(legend))

    def px(t: float) -> float:
        return left + (t - t0) / (t1 - t0) * (width - left - mr)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" width="{width}" '
           f'height="{height}" role="img" class="plot states" font-family="system-ui, sans-serif" '
           f'font-size="11"><title>states over time</title>'
           f'<rect width="{width}" height="{height}" fill="#fff"/>'
           f'<text x="{_n(left)}" y="14" font-weight="600">Which controller ran when</text>']
    for r, (label, marks) in enumerate(rows):
        y = mt + _ROW * r
        out.append(f'<text x="{_n(left - 6)}" y="{y + 12}" text-anchor="end" fill="#3a4450">'
                   f'{escape(printable(label)[:_ROW_LABEL])}</text>')
        for mark in marks:
            if isinstance(mark, tuple):
                k0, k1, text = mark
                x0, x1 = px(ts[k0]), px(ts[min(k1 + 1, n - 1)])
                colour = state_color(text)
                shown = escape(printable(text)[:40])
                out.append(f'<rect x="{_n(x0)}" y="{y + 1}" width="{_n(max(1.0, x1 - x0))}" height="14" '
                           f'fill="{colour}"><title>{shown}: {ts[k0]:.2f} to {ts[min(k1 + 1, n - 1)]:.2f} s'
                           f'</title></rect>')
            else:
                x0 = px(ts[mark])
                x1 = px(ts[min(mark + 1, n - 1)])
                out.append(f'<rect x="{_n(x0)}" y="{y + 4}" width="{_n(max(1.0, x1 - x0))}" height="8" '
                           f'fill="#1d2530"/>')
    out.append(f'<text x="{_n(left)}" y="{legend_y - 4}" fill="#555">{ts[0]:.0f} s</text>'
               f'<text x="{width - mr}" y="{legend_y - 4}" text-anchor="end" fill="#555">'
               f'{ts[-1]:.1f} s</text>')
    for r, line in enumerate(legend):  # as many lines as the names need: none is cut at the right edge
        for lx, text in line:
            y = legend_y + 20 * r
            out.append(f'<rect x="{_n(lx)}" y="{y + 4}" width="10" height="10" fill="{state_color(text)}"/>'
                       f'<text x="{_n(lx + 14)}" y="{y + 13}">{escape(printable(text)[:24])}</text>')
    out.append("</svg>")
    return Markup("".join(out))


def _legend_rows(names: list[str], width: int) -> list[list[tuple[float, str]]]:
    """The legend's names placed left to right, (x, name), starting a new line where one would pass the
    right edge."""
    rows: list[list[tuple[float, str]]] = [[]]
    lx = 6.0
    for text in names:
        room = 14 + _CHAR * len(printable(text)[:24])
        if rows[-1] and lx + room > width - 4:
            rows.append([])
            lx = 6.0
        rows[-1].append((lx, text))
        lx += room + 12
    return rows if rows[0] else []


def declared_plots(wanted: object, trace: dict) -> list[Markup]:
    """The plots of the declared signals and states that a check asked for (its result's `plots`, from
    Check.plots), drawn from `trace`: "states", and "signals:NAME,NAME" for those signals. An entry the
    report does not know, or a signal the trace lacks, draws nothing."""
    if not isinstance(wanted, list):
        return []
    out = []
    for entry in wanted[:8]:
        picture = None
        if entry == "states":
            picture = states_svg(trace)
        elif isinstance(entry, str) and entry.startswith("signals:"):
            picture = signals_svg(trace, [n for n in entry[len("signals:"):].split(",") if n][:12])
        if picture is not None:
            out.append(picture)
    return out
