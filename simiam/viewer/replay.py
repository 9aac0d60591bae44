"""Trace -> a self-contained replay page (Seam 2 in, one HTML file out; no network, no physics imports).

`simiam run` and the grader's report call `write_replay(trace, path)` / `render_replay(trace)`. The page has
the original Sim.I.am GUI's controls (home, rewind, play/pause, zoom buttons and mouse wheel, pan by dragging,
click the robot to follow it) plus a time slider, playback speed, keyboard shortcuts and plots linked to the
time cursor. Its script and style are inlined from `static/`, so the file opens offline and can be mailed;
pages written together (a batch) may load them from one shared copy instead (`assets`).
"""

from __future__ import annotations

import base64
import functools
import hashlib
import itertools
import json
import math
import zlib
from importlib import resources
from pathlib import Path
from typing import Any

import jinja2
from jinja2.utils import htmlsafe_json_dumps
from markupsafe import Markup

from simiam import safe_write
from simiam.robot.quickbot import IR_MOUNTS
from simiam.signals import WEEKS_1_TO_4, declared, from_headers, headers
from simiam.viewer.state_colours import state_colors

TRACE_FORMAT = "simiam-trace/1"

# Decimals kept when embedding (columnar, rounded): 0.1 mm in position, 1e-4 rad, 1e-3 rad/s; signals 1e-4.
_DIGITS = {"t": 4, "x": 4, "y": 4, "theta": 4, "x_est": 4, "y_est": 4, "theta_est": 4, "vel_r": 3, "vel_l": 3}
_SIGNAL_DIGITS = 4
_REQUIRED_STEPS = ("t", "x", "y", "theta")


class TraceFormatError(ValueError):
    """The dict handed to the viewer is not a Seam-2 trace; the message says what is missing."""


def _num(v: Any, digits: int) -> float | None:
    """A JSON-safe rounded number; None, NaN, inf and non-numbers become None (null in the page)."""
    if type(v) is float:  # the common case first: a report packs tens of thousands of numbers
        if v - v != 0.0:  # inf or nan
            return None
        r = round(v, digits)
        return 0.0 if r == 0 else r
    if v is None or isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    f = float(v)
    if not math.isfinite(f):
        return None
    r = round(f, digits)
    return 0.0 if r == 0 else r  # no "-0.0" in the page


# round(v, digits) converts through decimal text (~0.4 us a number; a report packs tens of thousands).
# Scaled, floored and divided back it costs half that and gives the same float: the product v * 10**digits
# is off the exact one by under _TIE while it stays below _FAST, so unless its fraction lies within _TIE of
# one half it rounds to the integer the exact one rounds to, and that integer over 10**digits (both exact)
# divides to the float nearest the decimal, which is what round() returns. Near a half, round() decides.
# tests/viewer/test_replay_rounding.py compares them on ~860 000 numbers, most of them at or next to a half.
_FAST, _TIE = 2.0 ** 33, 2.0 ** -19


def _column(values: list, digits: int) -> list:
    """_num of each value, finite floats (nearly every value) inline and without round()'s decimal text."""
    scale = 10.0 ** digits
    lo, hi = 0.5 - _TIE, 0.5 + _TIE
    return [(0.0 if (r := (f + 1.0 if d > 0.5 else f) / scale) == 0 else r)
            if type(v) is float and -_FAST < (y := v * scale) < _FAST
            and not lo < (d := y - (f := y // 1.0)) < hi
            else None if v is None else _num(v, digits) for v in values]


def _split(rows: list, n: int, width: int, digits: int) -> list[list]:
    """[[a0..a4], ...] -> width columns; a missing or short row gives nulls."""
    nothing = (None,) * width
    whole = [row if type(row) in (list, tuple) and len(row) >= width
             else nothing if row is None else _padded(row, width) for row in rows[:n]]
    whole += [nothing] * (n - len(whole))
    if not n:
        return [[] for _ in range(width)]
    # by columns (zip transposes at C speed; a longer row's extra entries are left out, as row by row)
    return [_column(list(column), digits) for column in itertools.islice(zip(*whole, strict=False), width)]


def _padded(row: Any, width: int) -> tuple:
    """A row that is not a whole list of `width` entries: its entries where it has them, None elsewhere."""
    ok = isinstance(row, (list, tuple))
    return tuple(row[j] if ok and len(row) > j else None for j in range(width))


def _states(states: list, n: int) -> list[list]:
    """Run-length encoding of the controller names: [[first_row, name], ...]."""
    runs: list[list] = []
    for k in range(min(n, len(states))):
        name = str(states[k]) if states[k] is not None else ""
        if not runs or runs[-1][1] != name:
            runs.append([k, name])
    return runs


def _signal_header(trace: dict) -> list[dict]:
    """The trace's declared signals (a trace without them recorded weeks 1-4's five)."""
    robot = trace.get("robot") or {}
    n_ir = len(robot.get("ir_mounts") or []) or len(IR_MOUNTS)
    raw = trace.get("signals")
    try:
        return from_headers(raw) if raw is not None else headers(declared(WEEKS_1_TO_4), n_ir)
    except ValueError as exc:
        raise TraceFormatError(str(exc)) from None


def _pack_signal(sig: dict, values: list, n: int) -> Any:
    """One signal's column in the page's form, or None if it never has a value: numbers (scalar, count;
    a flag as 1/0), run-length text (label), {"x": [...], "y": [...]} (vector2) or {"x": [[...] per
    column], "y": ...} (points)."""
    values = values[:n] + [None] * (n - len(values))
    if not any(v is not None for v in values):
        return None
    kind = sig["kind"]
    if kind in ("scalar", "count"):
        return _column(values, _SIGNAL_DIGITS)
    if kind == "flag":
        return [None if v is None else int(v is True) for v in values]
    if kind == "label":
        return _states([v if isinstance(v, str) else None for v in values], n)
    if kind == "vector2":
        xs, ys = _split(values, n, 2, _SIGNAL_DIGITS)
        return {"x": xs, "y": ys}
    size = sig["size"]
    rows_x = [p[0] if isinstance(p, (list, tuple)) and p else None for p in values]
    rows_y = [p[1] if isinstance(p, (list, tuple)) and len(p) > 1 else None for p in values]
    return {"x": _split(rows_x, n, size, _SIGNAL_DIGITS), "y": _split(rows_y, n, size, _SIGNAL_DIGITS)}


def thin_rows(trace: dict, max_rows: int) -> tuple[dict, int]:
    """(trace with at most ~max_rows rows, stride): every k-th row, plus the last and the first collided.

    For pages that embed several long runs (the grader's report); the standalone replay keeps every row.
    """
    steps = trace.get("steps") or {}
    n = len(steps.get("t") or [])
    stride = max(1, math.ceil(n / max(1, max_rows)))
    if stride == 1:
        return trace, 1
    keep = set(range(0, n, stride)) | {n - 1}
    collided = steps.get("collided") or []
    first_hit = next((k for k, c in enumerate(collided) if c is True), None)
    if first_hit is not None and first_hit < n:
        keep.add(first_hit)
    rows = sorted(keep)
    thin = {name: [col[k] for k in rows] if isinstance(col, list) and len(col) == n else col
            for name, col in steps.items()}
    return {**trace, "steps": thin}, stride


def pack_trace(trace: dict) -> dict:
    """The compact form embedded in the page: rounded numbers, one flat list per column, states run-length."""
    if not isinstance(trace, dict):
        raise TraceFormatError(f"a trace must be a JSON object (dict), not {type(trace).__name__}")
    fmt = trace.get("format")
    if fmt is not None and fmt != TRACE_FORMAT:
        raise TraceFormatError(f"trace format is {fmt!r}; this viewer reads {TRACE_FORMAT!r}")
    steps = trace.get("steps")
    if not isinstance(steps, dict):
        raise TraceFormatError("the trace has no 'steps' object (the columnar step table of Seam 2)")
    missing = [c for c in _REQUIRED_STEPS if not isinstance(steps.get(c), list)]
    if missing:
        raise TraceFormatError(f"the trace's steps lack the column(s) {', '.join(missing)}")
    n = len(steps["t"])
    if n == 0:
        raise TraceFormatError("the trace has no rows (steps.t is empty)")
    for c in ("x", "y", "theta"):
        if len(steps[c]) != n:
            raise TraceFormatError(f"steps.{c} has {len(steps[c])} rows but steps.t has {n}")
    robot = trace.get("robot")
    if not isinstance(robot, dict) or not robot.get("base_plate"):
        raise TraceFormatError("the trace has no robot.base_plate polygon to draw")

    cols: dict[str, list] = {}
    for name, digits in _DIGITS.items():
        vals = steps.get(name)
        if isinstance(vals, list) and any(v is not None for v in vals):
            cols[name] = _column(vals[:n] + [None] * (n - len(vals)), digits)
    for name in ("x_est", "y_est", "theta_est", "vel_r", "vel_l"):
        cols.setdefault(name, [None] * n)
    n_ir = len(robot.get("ir_mounts") or []) or len(IR_MOUNTS)
    if isinstance(steps.get("ir_range"), list):
        for k, column in enumerate(_split(steps["ir_range"], n, n_ir, 4)):
            cols[f"ir{k}"] = column
    signals, signal_data = [], {}
    for sig in _signal_header(trace):
        values = steps.get(sig["name"])
        packed_signal = _pack_signal(sig, values, n) if isinstance(values, list) else None
        if packed_signal is not None:
            signals.append(sig)
            signal_data[sig["name"]] = packed_signal

    def poly(p: list) -> list:
        return [[_num(v[0], 5), _num(v[1], 5)] for v in p]

    world = trace.get("world") or {}
    collision = trace.get("collision")
    if isinstance(collision, dict) and isinstance(collision.get("pose"), list):
        collision = {"step": collision.get("step"), "t": _num(collision.get("t"), 4) or 0.0,
                     "pose": [_num(v, 4) for v in collision["pose"][:3]]}
    else:
        collision = None
    mounts = [[_num(m[0], 5), _num(m[1], 5), _num(m[2], 6)] for m in robot.get("ir_mounts") or []]
    goal = trace.get("goal")
    if not (isinstance(goal, (list, tuple)) and len(goal) >= 2):
        goal = None
    obstacles = [poly(p) for p in world.get("obstacles", [])]
    states = _states(steps.get("state") or [], n)
    labels = [run for sig in signals if sig["kind"] == "label" for run in signal_data[sig["name"]]]
    return {
        "week": trace.get("week"), "dt": _num(trace.get("dt"), 6) or 0.033, "seconds": trace.get("seconds"),
        "world": {"name": str(world.get("name", "")), "obstacles": obstacles},
        "robot": {"base_plate": poly(robot["base_plate"]), "ir_mounts": mounts,
                  "ir_min_range": robot.get("ir_min_range", 0.04),
                  "ir_max_range": robot.get("ir_max_range", 0.3),
                  "ir_spread": robot.get("ir_spread", math.radians(6))},
        "start": trace.get("start"),
        "goal": [_num(goal[0], 5), _num(goal[1], 5)] if goal else None,
        "collision": collision,
        "states": states,
        "state_colors": state_colors(run[1] for run in states + labels),  # as the report colours them
        "steps": cols,
        "signals": signals,        # the declared signals that have values, in order (name, kind, unit)
        "signal_data": signal_data,
        "ending": _ending(trace.get("ending")),
    }


def _ending(ending: Any) -> dict | None:
    """How the run ended, for the page's status line (reason and time; the words only when it broke)."""
    if not isinstance(ending, dict) or not isinstance(ending.get("reason"), str):
        return None
    message = ending.get("message")
    return {"reason": ending["reason"][:40], "t": _num(ending.get("t"), 4),
            "message": message[:300] if isinstance(message, str) else ""}


@functools.cache
def _asset(name: str) -> str:
    return resources.files("simiam.viewer").joinpath(name).read_text(encoding="utf-8")


def _script() -> str:
    """The page's one script element's text, exactly (its hash is what the page's CSP allows to run)."""
    return "\n" + _asset("static/replay.js") + "\n"


def content_security_policy() -> str:
    """The replay page's Content-Security-Policy: its own inlined script may run and nothing else (no
    injected inline script or event handler, no fetch, no form, no plug-in). A page that embeds a replay
    in an iframe `srcdoc` must allow the same script hash: a srcdoc frame inherits its parent's policy."""
    digest = base64.b64encode(hashlib.sha256(_script().encode("utf-8")).digest()).decode("ascii")
    return (f"default-src 'none'; script-src 'sha256-{digest}'; style-src 'unsafe-inline'; "
            "img-src data:; base-uri 'none'; form-action 'none'")


def shared_policy() -> str:
    """The policy of a replay page that loads its script and styles from shared files (`assets`): scripts
    from the page's own origin only ('self': for a page opened from disk, local files; an inline script
    or event handler injected into the page still never runs), nothing fetched, no form, no plug-in.
    A hash cannot name an external script for a file:// page: Chromium checks a script's integrity only
    on a CORS request, which a file:// page cannot make."""
    return ("default-src 'none'; script-src 'self'; style-src 'self' 'unsafe-inline'; img-src data:; "
            "base-uri 'none'; form-action 'none'")


SHARED_ASSETS = ("replay.js", "replay.css")


def shared_assets() -> dict[str, str]:
    """The files a replay page rendered with `assets` loads (name -> text): written once for many pages
    (the batch's `assets/` folder)."""
    return {name: _asset(f"static/{name}") for name in SHARED_ASSETS}


def deflated_data(packed: dict) -> str:
    """The packed trace as a replay page with shared assets carries it: the JSON the self-contained page
    embeds (the same text, `tojson`'s), deflated (zlib) and base64-encoded, about a quarter of its size;
    the page's script unpacks it with the browser's DecompressionStream. Base64 holds no `<`, `&` or quote:
    nothing in it can end or change the element it is in."""
    text = str(htmlsafe_json_dumps(packed, **_env().policies["json.dumps_kwargs"]))
    return base64.b64encode(zlib.compress(text.encode("ascii"), 6)).decode("ascii")


def _encodable(value: Any) -> Any:
    if isinstance(value, str) and not isinstance(value, Markup):
        return value.encode("utf-8", "backslashreplace").decode("utf-8")
    return value


TEMPLATE = "templates/replay.html"
# the page's template as Python, made by `python -m grader.report.precompiled` (simiam.viewer.precompiled)
COMPILED = Path(__file__).with_name("compiled") / "replay_html.py"


@functools.lru_cache(maxsize=1)
def _template() -> jinja2.Template:
    """The page's template, loaded once per process (a report embeds one replay per run): precompiled
    where the stored code matches the template, else compiled as `from_string` does."""
    from simiam.viewer import precompiled

    env = _env()
    return precompiled.template(env, _asset(TEMPLATE), "simiam.viewer.compiled.replay_html",
                                globals=env.make_globals(None))


def _env() -> jinja2.Environment:
    # a title from a file name that is not UTF-8 (lone surrogates) is shown escaped, not a crash
    env = jinja2.Environment(autoescape=True, undefined=jinja2.StrictUndefined, finalize=_encodable)
    # the trace goes into a <script type="application/json"> through jinja2's tojson, which escapes < > & '
    # so that no text inside (a student's state name: "</script>", "<!--") can end or change the element;
    # ASCII-only, so that any text (lone surrogates too) is written as \u escapes JSON.parse reads back
    env.policies["json.dumps_kwargs"] = {"separators": (",", ":"), "allow_nan": False,
                                         "ensure_ascii": True, "sort_keys": False}
    return env


def render_replay(trace: dict, title: str | None = None, max_rows: int | None = None,
                  assets: str | None = None) -> str:
    """Return the replay page for a Seam-2 trace (a dict) as one self-contained HTML string.

    `max_rows` thins a long run to every k-th row (the grader's report embeds several runs); by default
    every row is kept. `assets` (a relative URL of a folder holding `shared_assets()`) makes the page load
    its script and styles from there instead of carrying them (~40 KB less a page, for pages written
    together: a batch) and carry its data deflated (`deflated_data`). Raises TraceFormatError with a
    plain message if `trace` is not a Seam-2 trace.
    """
    stride = 1
    if max_rows is not None and isinstance(trace, dict):
        trace, stride = thin_rows(trace, max_rows)
    packed = pack_trace(trace)
    meta = trace.get("meta") or {}
    week = trace.get("week")
    if title is None:
        title = f"simiam replay: week {week}" if week is not None else "simiam replay"
        if meta.get("submission"):
            title += f" ({meta['submission']})"
    n = len(packed["steps"]["t"])
    bits = [f"world {packed['world']['name']}" if packed["world"]["name"] else "",
            f"dt {packed['dt']} s", f"{n} rows"]
    if stride > 1:
        bits.append(f"1 step in {stride} shown")
    if meta.get("seed") is not None:
        bits.append(f"seed {meta['seed']}")
    subtitle = " · ".join(b for b in bits if b)
    if assets is not None:
        return _template().render(title=title, subtitle=subtitle, csp=shared_policy(), assets=assets,
                                  data=packed, deflated=deflated_data(packed))
    return _template().render(title=title, subtitle=subtitle, csp=content_security_policy(),
                              css=Markup(_asset("static/replay.css")), script=Markup(_script()), data=packed)


def write_replay(trace: dict, path: str | Path) -> Path:
    """Write the replay page for `trace` to `path` (parent folders created; never through a link,
    simiam.safe_write) and return the path."""
    return safe_write.write_text(path, render_replay(trace))


def main(argv: list[str] | None = None) -> int:
    """`python -m simiam.viewer.replay TRACE.json [OUT.html]`: a replay page for a saved trace."""
    import argparse
    import sys

    p = argparse.ArgumentParser(prog="python -m simiam.viewer.replay", description=main.__doc__)
    p.add_argument("trace", help="a trace JSON written by `simiam run` (runs/weekN.json) or the grader")
    p.add_argument("out", nargs="?", default=None, help="the page to write (default: TRACE with .html)")
    args = p.parse_args(argv)
    src = Path(args.trace)
    try:
        trace = json.loads(src.read_text(encoding="utf-8"))
        out = write_replay(trace, Path(args.out) if args.out else src.with_suffix(".html"))
    except OSError as exc:
        print(f"{src}: cannot read or write: {exc.strerror or exc}", file=sys.stderr)
        return 2
    except json.JSONDecodeError as exc:
        print(f"{src}, line {exc.lineno}: not valid JSON ({exc.msg})", file=sys.stderr)
        return 2
    except TraceFormatError as exc:
        print(f"{src}: not a simiam trace: {exc}", file=sys.stderr)
        return 2
    print(out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
