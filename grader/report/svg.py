"""Inline SVG plots for the grader's reports: readable offline, no script, text escaped by construction.

Every function returns `markupsafe.Markup` (safe to drop into an autoescaping jinja2 template) built only
from numbers and `html.escape`d labels. The batch summary page can reuse `histogram_svg` and
`pass_rate_svg`.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator, Sequence
from contextvars import ContextVar
from dataclasses import dataclass, field
from html import escape
from typing import TypeGuard

from markupsafe import Markup

BLUE, RED, GREEN, GREY, ORANGE = "#1f4fd1", "#d1242f", "#1a7f37", "#8a8f98", "#b35900"
_FONT = 'font-family="system-ui, sans-serif" font-size="11"'
_LEGEND_STRIP = 20  # px under a top view for its legend


def _n(v: float) -> str:
    """A coordinate with at most two decimals (pixels), without '-0'."""
    s = f"{v:.2f}"
    if s[-1] != "0":  # most coordinates: nothing to strip (a plot formats thousands)
        return s
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _n1(v: float) -> str:
    """A coordinate with one decimal (compact plots), without '-0'."""
    s = f"{v:.1f}"
    if s.endswith(".0"):
        s = s[:-2]
    return "0" if s == "-0" else s


# Compact plots (the batch's student pages, which must stay small): at most COMPACT_POINTS points a line
# (or fewer, as asked), one decimal a coordinate, straight stretches drawn by their ends. Off by default: a
# report written by `grade weekN` draws every plot as before.
COMPACT_POINTS = 250
_COMPACT: ContextVar[int] = ContextVar("compact_plots", default=0)


@contextlib.contextmanager
def compact_plots(points: int = COMPACT_POINTS) -> Iterator[None]:
    """Draw the plots made inside this block compact, with at most `points` points a line: a fraction of
    the bytes, the same picture at screen resolution."""
    token = _COMPACT.set(max(2, int(points)))
    try:
        yield
    finally:
        _COMPACT.reset(token)


# No quantity of a run of this robot comes near a million (metres, seconds, rad/s, counts); a student's
# debug value can be any finite float, up to 1.8e308, and the difference of two such overflows to inf. A
# value beyond this is left out of a plot, which says how many it left out, rather than flattening every
# other value into a line or breaking the axis arithmetic.
OFF_CHART = 1e6


def _finite(v) -> TypeGuard[float]:
    if type(v) is float:  # the common case first: a plot calls this once per point
        return v - v == 0.0  # False for inf and nan only
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _plottable(v) -> TypeGuard[float]:
    """A number a plot draws: finite and within ±OFF_CHART."""
    return _finite(v) and -OFF_CHART <= v <= OFF_CHART


def _off_chart(v) -> bool:
    """A finite number too large to draw: the plot counts it and says so."""
    return _finite(v) and not -OFF_CHART <= v <= OFF_CHART


def _label(v: float) -> str:
    a = abs(v)
    if a >= 100 or a == 0:
        return f"{v:.0f}"
    return f"{v:.2f}" if a < 10 else f"{v:.1f}"


def _ticks(lo: float, hi: float, count: int = 4) -> list[float]:
    raw = (hi - lo) / max(count, 1)
    if raw <= 0:
        return [lo]
    p = 10 ** math.floor(math.log10(raw))
    step = p * min((m for m in (1, 2, 5, 10) if m * p >= raw), default=10)
    first = math.ceil(lo / step) * step
    return [first + k * step for k in range(int((hi - first) / step + 1e-9) + 1)]


def _downsample(xs: Sequence, ys: Sequence, limit: int = 600) -> list[tuple[float, float | None]]:
    """At most ~limit points, keeping every gap (None) so broken lines stay broken."""
    n = min(len(xs), len(ys))
    stride = max(1, math.ceil(n / limit))
    out = [(xs[k], y if (-OFF_CHART <= y <= OFF_CHART if type(y := ys[k]) is float else _plottable(y))
            else None) for k in range(0, n, stride)]
    if n and (n - 1) % stride:
        out.append((xs[n - 1], ys[n - 1] if _plottable(ys[n - 1]) else None))
    return out


@dataclass
class Series:
    """One line of a plot: y against x, with a legend label; `wrap` breaks the line at ±π jumps."""

    label: str
    xs: Sequence[float]
    ys: Sequence[float | None]
    color: str = BLUE
    dash: str = ""
    width: float = 1.6
    wrap: bool = False


@dataclass
class Chart:
    """A line chart with axes; `bands` are shaded (x, lo, hi) polygons, `vlines` are (x, colour, label)."""

    series: list[Series]
    title: str = ""
    x_label: str = ""
    y_label: str = ""
    width: int = 460
    height: int = 240
    bands: list[tuple[list[float], list[float | None], list[float | None], str]] = field(default_factory=list)
    vlines: list[tuple[float, str, str]] = field(default_factory=list)

    def render(self) -> Markup:
        legend = _legend_lines([s.label for s in self.series], 46 + 6, self.width - 10)
        ml, mr, mt, mb = 46, 10, 22 if self.title else 8, 34
        # a legend longer than the chart is wide takes more lines below it
        extra = 16 * max((line for _, line in legend), default=0)
        sources = [(s.xs, s.ys) for s in self.series]
        for bxs, los, his, _ in self.bands:  # a band's points: (x, lo) and (x, hi), row by row
            rows = list(zip(bxs, los, his, strict=False))
            sources.append(([x for x, _, _ in rows for _ in (0, 1)],
                            [v for _, lo, hi in rows for v in (lo, hi)]))
        off, (x0, x1, y0, y1) = _extent(sources)
        if x1 - x0 < 1e-12:
            x0, x1 = x0 - 0.5, x1 + 0.5
        if y1 - y0 < 1e-12:
            y0, y1 = y0 - 0.5, y1 + 0.5
        pad = 0.05 * (y1 - y0)
        y0, y1 = y0 - pad, y1 + pad
        w, h = self.width, self.height + extra
        mb += extra

        def px(x: float) -> float:
            return ml + (x - x0) / (x1 - x0) * (w - ml - mr)

        def py(y: float) -> float:
            return mt + (y1 - y) / (y1 - y0) * (h - mt - mb)

        out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w} {h}" width="{w}" height="{h}" '
               f'role="img" class="plot" {_FONT}><title>{escape(self.title or self.y_label)}</title>',
               f'<rect x="0" y="0" width="{w}" height="{h}" fill="#fff"/>']
        if self.title:
            out.append(f'<text x="{ml}" y="14" font-weight="600">{escape(self.title)}</text>')
        for t in _ticks(y0, y1):
            out.append(f'<line x1="{ml}" x2="{w - mr}" y1="{_n(py(t))}" y2="{_n(py(t))}" stroke="#e6e9ee"/>'
                       f'<text x="{ml - 4}" y="{_n(py(t) + 3.5)}" text-anchor="end" fill="#555">'
                       f'{_label(t)}</text>')
        for t in _ticks(x0, x1, 6):  # a label centred on the right edge would stick out: ends there instead
            x, anchor = (w - 2, "end") if px(t) + 4 * len(_label(t)) > w - 2 else (px(t), "middle")
            out.append(f'<text x="{_n(x)}" y="{h - mb + 13}" text-anchor="{anchor}" fill="#555">'
                       f'{_label(t)}</text>')
        out.append(f'<rect x="{ml}" y="{mt}" width="{w - ml - mr}" height="{h - mt - mb}" fill="none" '
                   f'stroke="#c5cbd3"/>')
        for xs, los, his, color in self.bands:
            out.extend(_band(xs, los, his, color, px, py))
        if off:  # top right, inside the frame: the plot says what it left out
            values = f"{off} value{'s' if off != 1 else ''}"
            out.append(f'<text x="{w - mr - 4}" y="{mt + 12}" text-anchor="end" fill="{ORANGE}">'
                       f'{values} off the chart (beyond ±{OFF_CHART:,.0f})</text>')
        for x, color, label in self.vlines:
            if _finite(x) and x0 <= x <= x1:
                out.append(f'<line x1="{_n(px(x))}" x2="{_n(px(x))}" y1="{mt}" y2="{h - mb}" '
                           f'stroke="{color}" stroke-dasharray="4 3"/>'
                           f'<text x="{_n(px(x) + 3)}" y="{mt + 11}" fill="{color}">{escape(label)}</text>')
        for s in self.series:
            for d in _paths(s, px, py):
                dash = f' stroke-dasharray="{s.dash}"' if s.dash else ""
                out.append(f'<path d="{d}" fill="none" stroke="{s.color}" stroke-width="{s.width}"{dash}/>')
        for s, (lx, row) in zip(self.series, legend, strict=True):  # legend along the bottom
            dash = f' stroke-dasharray="{s.dash}"' if s.dash else ""
            y = h - extra + 16 * row
            out.append(f'<line x1="{_n(lx)}" x2="{_n(lx + 16)}" y1="{y - 7}" y2="{y - 7}" '
                       f'stroke="{s.color}" stroke-width="2"{dash}/>'
                       f'<text x="{_n(lx + 20)}" y="{y - 3}">{escape(s.label)}</text>')
        if self.x_label:  # in the corner under the y labels, clear of the ticks and the legend
            out.append(f'<text x="{ml - 10}" y="{h - mb + 13}" text-anchor="end" fill="#555">'
                       f'{escape(self.x_label)}</text>')
        out.append("</svg>")
        return Markup("".join(out))


def _plottable_each(values: Sequence, n: int) -> list[bool]:
    """_plottable of each of the first n values; a float (nearly every value) inline, without the call."""
    return [-OFF_CHART <= v <= OFF_CHART if type(v) is float else _plottable(v) for v in values[:n]]


def _extent(sources: list[tuple[Sequence, Sequence]],
            empty: tuple[float, float, float, float] = (0.0, 1.0, 0.0, 1.0)) -> tuple[int, tuple]:
    """(how many points are off the chart, (x0, x1, y0, y1)) of the (x, y) points of every (xs, ys) in
    `sources`, in order: the smallest and largest plottable coordinates of the points plottable in both
    (`empty` without one), the first of equal ones as min() and max() pick over all the points at once.
    A point is off the chart when one coordinate is finite and the other beyond OFF_CHART."""
    off, lows, highs = 0, [], []
    flags: dict[tuple[int, int], list[bool]] = {}  # a chart's series share their xs: judged once
    for xs, ys in sources:
        n = min(len(xs), len(ys))
        fx = flags.get((id(xs), n)) or flags.setdefault((id(xs), n), _plottable_each(xs, n))
        fy = _plottable_each(ys, n)
        if all(fx) and all(fy):  # the common case: every point drawn, none off the chart
            kx, ky = xs[:n], ys[:n]
        else:
            both = [a and b for a, b in zip(fx, fy, strict=True)]
            kx = [x for x, ok in zip(xs, both, strict=False) if ok]
            ky = [y for y, ok in zip(ys, both, strict=False) if ok]
            off += sum(1 for x, y, ok in zip(xs, ys, both, strict=False) if not ok
                       and ((_off_chart(x) and _finite(y)) or (_off_chart(y) and _finite(x))))
        if len(kx):
            lows.append((min(kx), min(ky)))
            highs.append((max(kx), max(ky)))
    if not lows:
        return off, empty
    # min() and max() over the sources' own, in order: the first of equal values wins, as over them all
    return off, (min(lo[0] for lo in lows), max(hi[0] for hi in highs),
                 min(lo[1] for lo in lows), max(hi[1] for hi in highs))


LEGEND_CHAR = 7.0  # px per character of an 11 px legend label, generously


def _legend_lines(labels: Sequence[str], left: float, right: float) -> list[tuple[float, int]]:
    """(x, line) of each legend entry: left to right, a new line where an entry would pass `right` (the
    week-6 legend "u_fw x, u_fw y, u_fw_t x..." ran off the chart)."""
    out: list[tuple[float, int]] = []
    lx, line = left, 0
    for label in labels:
        room = 20 + LEGEND_CHAR * len(label)
        if lx > left and lx + room > right:
            lx, line = left, line + 1
        out.append((lx, line))
        lx += room + 14
    return out


def _paths(s: Series, px, py) -> list[str]:
    compact = _COMPACT.get()
    segments: list[list[tuple[float, float]]] = []
    cur: list[tuple[float, float]] = []
    prev = None
    for x, y in _downsample(s.xs, s.ys, compact or 600):
        drawn = -OFF_CHART <= x <= OFF_CHART if type(x) is float else _plottable(x)
        if y is None or not drawn or (s.wrap and prev is not None and abs(y - prev) > math.pi):
            if len(cur) > 1:
                segments.append(cur)
            cur = []
        if y is not None and drawn:
            cur.append((px(x), py(y)))
        prev = y
    if len(cur) > 1:
        segments.append(cur)
    return ["M" + " L".join(_coordinates(seg, compact, " ")) for seg in segments]


def _coordinates(points: list[tuple[float, float]], compact: int, sep: str) -> list[str]:
    """Pixel points as SVG text: two decimals each; in compact plots (compact_plots) one decimal, with
    the points that lie on the line through their neighbours left out (a straight or flat stretch)."""
    if not compact:
        return [f"{_n(x)}{sep}{_n(y)}" for x, y in points]
    return [f"{_n1(x)}{sep}{_n1(y)}" for x, y in _simplified(points)]


def _simplified(points: list[tuple[float, float]], tolerance: float = 0.5) -> list[tuple[float, float]]:
    """`points` with only those kept that the line needs to pass within `tolerance` px of every point
    (Douglas-Peucker): what is left draws the same line at screen resolution. Plain Python: on a line's
    few hundred points it is faster than numpy's per-call overhead."""
    n = len(points)
    if n < 3:
        return points
    keep = [False] * n
    keep[0] = keep[-1] = True
    spans = [(0, n - 1)]
    while spans:
        i, j = spans.pop()
        if j - i < 2:
            continue
        ax, ay = points[i]
        bx, by = points[j]
        dx, dy = bx - ax, by - ay
        length = math.hypot(dx, dy)
        far, at = -1.0, i
        for k in range(i + 1, j):
            x, y = points[k]
            # from the segment's line; where it ends where it began (a loop), from that point
            gap = abs((x - ax) * dy - (y - ay) * dx) if length else math.hypot(x - ax, y - ay)
            if gap > far:
                far, at = gap, k
        if (far / length if length else far) > tolerance:
            keep[at] = True
            spans += [(i, at), (at, j)]
    return [p for p, kept in zip(points, keep, strict=True) if kept]


def _band(xs, los, his, color, px, py) -> list[str]:
    """Shaded area between lo and hi, split wherever either is missing or jumps by more than π."""
    out: list[str] = []
    seg: list[tuple[float, float, float]] = []

    def flush() -> None:
        if len(seg) > 1:
            top = " L".join(f"{_n(px(x))} {_n(py(hi))}" for x, _, hi in seg)
            bottom = " L".join(f"{_n(px(x))} {_n(py(lo))}" for x, lo, _ in reversed(seg))
            out.append(f'<path d="M{top} L{bottom} Z" fill="{color}" stroke="none"/>')

    n = min(len(xs), len(los), len(his))
    for k in range(0, n, max(1, math.ceil(n / 600))):
        x, lo, hi = xs[k], los[k], his[k]
        ok = _plottable(x) and _plottable(lo) and _plottable(hi)
        if not ok or (seg and abs(lo - seg[-1][1]) > math.pi):
            flush()
            seg = []
        if ok:
            seg.append((x, lo, hi))
    flush()
    return out


def _wrap(a: float) -> float:
    return math.atan2(math.sin(a), math.cos(a))


def trajectory_svg(trace: dict, size: int = 360) -> Markup:
    """Top view of one run: obstacles, goal, true path (solid), odometry estimate (dashed), start, end,
    and the collision marked with a red cross."""
    steps = trace.get("steps") or {}
    xs, ys = steps.get("x") or [], steps.get("y") or []
    obstacles = (trace.get("world") or {}).get("obstacles") or []
    corners = [(x, y) for poly in obstacles for x, y in poly]
    sources = [([x for x, _ in corners], [y for _, y in corners]), (xs, ys)]
    goal = trace.get("goal")
    if goal:
        sources.append(([goal[0]], [goal[1]]))
    _, (x0, x1, y0, y1) = _extent(sources, empty=(-1.0, 1.0, -1.0, 1.0))
    span = max(x1 - x0, y1 - y0, 0.2) * 1.06
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    scale = size / span

    def sx(x: float) -> float:
        return size / 2 + (x - cx) * scale

    def sy(y: float) -> float:
        return size / 2 - (y - cy) * scale

    # the legend has a strip of its own under the map: drawn on the map it would cover the walls
    height = size + _LEGEND_STRIP
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {size} {height}" width="{size}" '
           f'height="{height}" role="img" class="plot trajectory" {_FONT}><title>trajectory</title>'
           f'<rect width="{size}" height="{height}" fill="#fff"/>'
           f'<rect width="{size}" height="{size}" fill="#fff" stroke="#c5cbd3"/>']
    for poly in obstacles:
        d = " ".join(f"{_n(sx(x))},{_n(sy(y))}" for x, y in poly if _finite(x) and _finite(y))
        out.append(f'<polygon points="{d}" fill="#9aa3ae" stroke="#5b6573" stroke-width="0.8"/>')
    est = _polyline(steps.get("x_est") or [], steps.get("y_est") or [], sx, sy)
    if est:
        out.append(f'<polyline points="{est}" fill="none" stroke="{GREY}" stroke-width="1.3" '
                   f'stroke-dasharray="4 3"/>')
    true = _polyline(xs, ys, sx, sy)
    if true:
        out.append(f'<polyline points="{true}" fill="none" stroke="{BLUE}" stroke-width="1.8"/>')
    if goal and _plottable(goal[0]) and _plottable(goal[1]):
        gx, gy = sx(goal[0]), sy(goal[1])
        out.append(f'<circle cx="{_n(gx)}" cy="{_n(gy)}" r="6" fill="none" stroke="{GREEN}" '
                   f'stroke-width="2"/>'
                   f'<circle cx="{_n(gx)}" cy="{_n(gy)}" r="2" fill="{GREEN}"/>'
                   f'<text x="{_n(gx + 8)}" y="{_n(gy - 6)}" fill="{GREEN}">goal</text>')
    if xs and _finite(xs[0]) and _finite(ys[0]):
        out.append(f'<circle cx="{_n(sx(xs[0]))}" cy="{_n(sy(ys[0]))}" r="3.5" fill="#fff" stroke="{BLUE}" '
                   f'stroke-width="1.5"><title>start</title></circle>')
    if xs and _finite(xs[-1]) and _finite(ys[-1]):
        out.append(f'<circle cx="{_n(sx(xs[-1]))}" cy="{_n(sy(ys[-1]))}" r="3.5" fill="{BLUE}">'
                   f'<title>end</title></circle>')
    col = c if isinstance(c := trace.get("collision"), dict) else {}
    pose = col.get("pose")
    if isinstance(pose, list) and len(pose) >= 2 and all(_finite(v) for v in pose[:2]):
        x, y = sx(pose[0]), sy(pose[1])
        t = col.get("t")
        label = f"collision at t = {t:.2f} s" if _finite(t) else "collision"
        # the label sits above the cross (below it near the top), on the side with room for it, with a
        # white halo: readable over a wall or the path, never running off the map
        room_right = x + 9 + 6.5 * len(label) <= size
        lx, anchor = (x + 9, "start") if room_right else (x - 9, "end")
        ly = y - 10 if y > 24 else y + 20
        out.append(f'<path d="M{_n(x - 6)} {_n(y - 6)} L{_n(x + 6)} {_n(y + 6)} M{_n(x + 6)} {_n(y - 6)} '
                   f'L{_n(x - 6)} {_n(y + 6)}" stroke="{RED}" stroke-width="2.5"/>'
                   f'<text x="{_n(lx)}" y="{_n(ly)}" text-anchor="{anchor}" fill="{RED}" font-weight="600" '
                   f'stroke="#fff" stroke-width="3" paint-order="stroke">{escape(label)}</text>')
    out.append(f'<g class="legend" transform="translate(6 {size + _LEGEND_STRIP - 7})">'
               f'<line x1="0" x2="16" y1="-4" y2="-4" stroke="{BLUE}" '
               f'stroke-width="2"/><text x="20" y="0">true path</text><line x1="86" x2="102" y1="-4" y2="-4" '
               f'stroke="{GREY}" stroke-dasharray="4 3" stroke-width="1.5"/><text x="106" y="0">odometry'
               f'</text></g></svg>')
    return Markup("".join(out))


def _polyline(xs: Sequence, ys: Sequence, sx, sy) -> str:
    compact = _COMPACT.get()
    pts = [(sx(x), sy(y)) for x, y in _downsample(xs, ys, compact or 800)
           if y is not None and _plottable(x)]
    return " ".join(_coordinates(pts, compact, ","))


def heading_svg(trace: dict, goal: Sequence[float] | None = None, settle_time: float | None = None,
                band: float = 0.1) -> Markup:
    """θ against θ_g over time, with the course's settle band |θ − θ_g| < band·|θ_g| shaded.

    θ is the TRUE heading and θ_g the heading from the true position to the goal when a goal is known
    (how the grader measures settle time and overshoot); otherwise the trace's own theta_g column is used.
    The estimate's θ is drawn faintly for comparison.
    """
    steps = trace.get("steps") or {}
    ts = steps.get("t") or []
    goal = goal or trace.get("goal")
    theta = [_wrap(v) if _finite(v) else None for v in steps.get("theta") or []]
    est = [_wrap(v) if _finite(v) else None for v in steps.get("theta_est") or []]
    if goal and _finite(goal[0]) and _finite(goal[1]):
        ref = [math.atan2(goal[1] - y, goal[0] - x) if _finite(x) and _finite(y) else None
               for x, y in zip(steps.get("x") or [], steps.get("y") or [], strict=False)]
        ref_label = "θ_g (true position to goal)"
    else:
        ref = [v if _finite(v) else None for v in steps.get("theta_g") or []]
        ref_label = "θ_g (your controller)"
    lo = [r - band * abs(r) if r is not None else None for r in ref]
    hi = [r + band * abs(r) if r is not None else None for r in ref]
    series = [Series("θ (true)", ts, theta, BLUE, wrap=True),
              Series(ref_label, ts, ref, RED, dash="6 4", wrap=True),
              Series("θ (estimate)", ts, est, GREY, width=1.0, wrap=True)]
    vlines = [(settle_time, GREEN, f"settled {settle_time:.2f} s")] if _finite(settle_time) else []
    return Chart(series, title=f"Heading θ against θ_g (band ±{band:.0%} of θ_g)", x_label="t (s)",
                 bands=[(list(ts), lo, hi, "rgba(209,36,47,0.12)")], vlines=vlines).render()


def angle_svg(trace: dict, theta_d: float) -> Markup:
    """θ against a fixed target θ_d over time (week 2's go-to-angle runs): the TRUE heading, which the
    grader judges, and the estimate's θ faintly."""
    steps = trace.get("steps") or {}
    ts = list(steps.get("t") or [])
    theta = [_wrap(v) if _finite(v) else None for v in steps.get("theta") or []]
    est = [_wrap(v) if _finite(v) else None for v in steps.get("theta_est") or []]
    series = [Series("θ (true)", ts, theta, BLUE, wrap=True),
              Series("θ_d", ts, [_wrap(theta_d)] * len(ts), RED, dash="6 4"),
              Series("θ (estimate)", ts, est, GREY, width=1.0, wrap=True)]
    return Chart(series, title="Heading θ against θ_d", x_label="t (s)").render()


def histogram_svg(scores: Sequence[float], max_score: float, bins: int = 10, width: int = 520,
                  height: int = 200, title: str = "Scores") -> Markup:
    """Histogram of submission scores over [0, max_score] in `bins` equal bins (the top bin includes max)."""
    counts = [0] * bins
    for s in scores:
        if _finite(s) and max_score > 0:
            counts[min(bins - 1, max(0, int(s / max_score * bins)))] += 1
    # mt leaves a line for the count above the tallest bar below the title (font 11: the title's baseline
    # at 14, the count's at mt - 3); mr keeps the last tick's label (max_score, centred) inside the picture
    ml, mr, mb, mt = 34, 22, 30, 34
    peak = max(counts) or 1
    bw = (width - ml - mr) / bins
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" width="{width}" '
           f'height="{height}" role="img" class="plot histogram" {_FONT}><title>{escape(title)}</title>'
           f'<text x="{ml}" y="14" font-weight="600">{escape(title)}</text>']
    for k, c in enumerate(counts):
        bh = (height - mt - mb) * c / peak
        x = ml + k * bw
        lo, hi = max_score * k / bins, max_score * (k + 1) / bins
        out.append(f'<rect x="{_n(x + 1)}" y="{_n(height - mb - bh)}" width="{_n(bw - 2)}" height="{_n(bh)}" '
                   f'fill="{BLUE}"><title>{_label(lo)}–{_label(hi)}: {c}</title></rect>')
        if c:
            out.append(f'<text x="{_n(x + bw / 2)}" y="{_n(height - mb - bh - 3)}" '
                       f'text-anchor="middle">{c}</text>')
        out.append(f'<text x="{_n(x)}" y="{height - mb + 13}" text-anchor="middle" fill="#555">'
                   f'{_label(lo)}</text>')
    out.append(f'<text x="{_n(ml + bins * bw)}" y="{height - mb + 13}" text-anchor="middle" fill="#555">'
               f'{_label(max_score)}</text><line x1="{ml}" x2="{_n(ml + bins * bw)}" y1="{height - mb}" '
               f'y2="{height - mb}" stroke="#555"/><text x="{ml}" y="{height - 3}" fill="#555">score</text>'
               f'<text x="4" y="{mt + 4}" fill="#555">{peak}</text></svg>')
    return Markup("".join(out))


def pass_rate_svg(rates: Sequence[tuple[str, float]], width: int = 620,
                  title: str = "Pass rate per check") -> Markup:
    """Horizontal bars: for each (check label, fraction passed in 0..1), one bar with its percentage."""
    row, ml, mt = 20, min(300, 12 + 6.3 * max((len(lbl) for lbl, _ in rates), default=4)), 24
    height = mt + row * len(rates) + 8
    bar_w = width - ml - 50
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" width="{width}" '
           f'height="{height}" role="img" class="plot pass-rates" {_FONT}><title>{escape(title)}</title>'
           f'<text x="4" y="14" font-weight="600">{escape(title)}</text>']
    for k, (label, rate) in enumerate(rates):
        r = min(1.0, max(0.0, rate)) if _finite(rate) else 0.0
        y = mt + k * row
        color = GREEN if r >= 0.8 else ORANGE if r >= 0.5 else RED
        out.append(f'<text x="{_n(ml - 6)}" y="{y + 13}" text-anchor="end">{escape(label)}</text>'
                   f'<rect x="{_n(ml)}" y="{y + 3}" width="{_n(bar_w)}" height="{row - 6}" fill="#eef0f3"/>'
                   f'<rect x="{_n(ml)}" y="{y + 3}" width="{_n(bar_w * r)}" height="{row - 6}" '
                   f'fill="{color}"/>'
                   f'<text x="{_n(ml + bar_w + 4)}" y="{y + 13}">{r:.0%}</text>')
    out.append("</svg>")
    return Markup("".join(out))
