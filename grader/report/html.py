"""The grader's HTML report for one submission: summary, checks table, and per-check details with plots.

`render_report(result, traces)` returns the page; `write_report(result, traces, path)` writes it. `result` is
the contract's result JSON; `traces` maps trace keys to Seam-2 traces (dicts). A check's runs are found as
`traces[check_id]`, `traces[check_id + "#2"]`, ... (what `grader.scenarios.keep` stores), or under the names
listed in `details["traces"]`. Run k of a check lines up with `details["runs"][k]` for its metrics.

Everything a student controls (messages, details, printed output, the submission name) reaches the page
only through the template: made visible by `printable` (the `finalize` hook) and escaped by jinja2's
autoescape, never pasted into rendered HTML; the page's Content-Security-Policy lets no script run but the
embedded replays' own. The plots are inline SVG built from numbers (grader.report.svg), readable offline.
Each scenario run gets an embedded replay (simiam.viewer.replay in an iframe `srcdoc`), thinned so that
the report stays small; `replays="files"` writes the replay pages next to the report and links them.
"""

from __future__ import annotations

import functools
import json
import math
import re
from pathlib import Path
from typing import Any

import jinja2
from markupsafe import Markup

from grader.report import svg
from grader.report.loader import PrecompiledLoader
from grader.report.signal_plots import declared_plots
from grader.untrusted import printable
from simiam import safe_write
from simiam.course.weeks import hidden_variants

# Metrics the scenario checks report, in the order shown, with how to print them.
METRICS: dict[str, tuple[str, str]] = {
    "reached": ("reached the goal", "bool"),
    "time_to_goal": ("time to goal", "s"),
    "final_distance": ("final distance", "m"),
    "min_clearance": ("minimum clearance", "m"),
    "settle_time": ("settle time", "s"),
    "overshoot": ("overshoot", "%"),
    "collided": ("collided", "bool"),
    "heading_error": ("heading error", "rad"),
    "path_length": ("distance driven", "m"),
    "max_displacement": ("furthest from start", "m"),
    "seconds": ("simulated", "s"),
}
RUN_LABELS = ("label", "goal", "theta_d", "world")
# Rows per embedded replay: at most 1000, and about 3000 over the whole report, so a report with four 60 s
# runs stays well under 1 MB (each thinned to every 3rd step); short runs keep every step.
REPLAY_ROWS, REPORT_ROWS = 1000, 3000
# A batch's student page (render_report_pages) aims at PAGE_BYTES: its plots are drawn compact with the
# first number of points a line that fits (what the student's code printed can still take it over).
PAGE_BYTES, PAGE_PLOT_POINTS = 150_000, (250, 150, 80)
STATUS_WORDS = {"passed": "passed", "failed": "failed", "error": "error", "timeout": "timed out"}
# Pages with no script of their own (the class summary, the fallback page) get this policy: even if some
# text escaped the templates' autoescape, a browser would run no script and load nothing from it.
STATIC_PAGE_CSP = "default-src 'none'; style-src 'unsafe-inline'; base-uri 'none'; form-action 'none'"


def page_text(value: Any) -> Any:
    """The templates' `finalize`: every plain string a page shows goes through `printable` (a student's
    bidi override or escape sequence is shown, not obeyed), then autoescape. Markup (the plots, text the
    template escaped itself with `|e`) passes as it is."""
    return printable(value) if isinstance(value, str) and not isinstance(value, Markup) else value


@functools.lru_cache(maxsize=1)
def _env() -> jinja2.Environment:
    """The report's environment, built once per process: its templates compile on first use and stay
    compiled (36 ms a report otherwise); a fresh process takes them precompiled (grader.report.loader)
    where they are up to date. Nothing in it depends on a result: every value reaches the
    templates as a render argument, still autoescaped and passed through `page_text`."""
    env = jinja2.Environment(loader=PrecompiledLoader("grader.report", "templates"), autoescape=True,
                             undefined=jinja2.ChainableUndefined, trim_blocks=True, lstrip_blocks=True,
                             finalize=page_text)
    env.filters["num"] = _num
    return env


def _num(v: Any, digits: int = 3) -> str:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return "–" if v is None else str(v)
    if not math.isfinite(v):
        return str(v)
    return f"{v:.{digits}f}".rstrip("0").rstrip(".") if isinstance(v, float) else str(v)


def format_metric(key: str, value: Any) -> str:
    """A metric as a student reads it: units, percentages, yes/no, '–' for not measured."""
    unit = METRICS.get(key, ("", ""))[1]
    if value is None:
        return "never" if key in ("time_to_goal", "settle_time") else "–"
    if unit == "bool":
        return "yes" if value else "no"
    if unit == "%" and isinstance(value, (int, float)):
        return f"{100 * value:.1f} %"
    if isinstance(value, (list, tuple)):
        return "(" + ", ".join(_num(v) for v in value) + ")"
    text = _num(value)
    return f"{text} {unit}" if unit and isinstance(value, (int, float)) else text


def _case_text(case: Any) -> list[tuple[str, str]]:
    if isinstance(case, dict):
        return [(str(k), json.dumps(v) if not isinstance(v, str) else v) for k, v in case.items()]
    return [("input", json.dumps(case) if not isinstance(case, str) else case)]


def _runs(details: dict) -> list[dict]:
    runs = details.get("runs")
    if isinstance(runs, list):
        return [r for r in runs if isinstance(r, dict)]
    if any(k in details for k in METRICS):
        return [details]
    return []


def _metric_table(runs: list[dict], names: list[str]) -> dict | None:
    """Columns (label, key) present in any run, rows of formatted values; None if there is nothing to show.
    `names` (the runs' trace labels) head the rows when the runs carry no label of their own."""
    if not runs:
        return None
    labels = [k for k in RUN_LABELS if any(k in r for r in runs)]
    if not labels and len(names) == len(runs):
        runs = [{"run": name, **r} for name, r in zip(names, runs, strict=True)]
        labels = ["run"]
    keys = [k for k in METRICS if any(k in r for r in runs)]
    if not keys:
        return None
    cols = [(k, k) for k in labels] + [(METRICS[k][0], k) for k in keys]
    rows = []
    for r in runs:
        cells = [format_metric(k, r.get(k)) for _, k in cols]
        rows.append({"cells": cells, "problem": r.get("problem") or ""})
    return {"cols": [c for c, _ in cols], "rows": rows}


def _trace_keys(check: dict, traces: dict) -> list[str]:
    listed = (check.get("details") or {}).get("traces")
    if isinstance(listed, list):
        return [k for k in listed if isinstance(k, str) and k in traces]
    cid = str(check.get("id", ""))
    keys = [k for k in traces if k == cid or k.startswith(cid + "#")]

    def order(k: str) -> int:
        return int(k.split("#", 1)[1]) if "#" in k and k.split("#", 1)[1].isdigit() else 1

    return sorted(keys, key=order)


def _same_goal(check: dict, traces: dict) -> list[str]:
    """The first kept run whose goal is this check's `details["goal"]` (the settle/overshoot checks)."""
    goal = (check.get("details") or {}).get("goal")
    if not isinstance(goal, (list, tuple)) or len(goal) < 2:
        return []
    for key, trace in traces.items():
        tg = trace.get("goal") if isinstance(trace, dict) else None
        if isinstance(tg, (list, tuple)) and len(tg) >= 2 and \
                all(isinstance(a, (int, float)) and isinstance(b, (int, float)) and abs(a - b) < 1e-9
                    for a, b in zip(tg[:2], goal[:2], strict=True)):
            return [key]
    return []


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text).strip("_") or "run"


def run_anchor(trace_key: str) -> str:
    """The id of the section holding a run's replay in the report (`report.html#<id>`); the batch summary
    links each student's replays with it."""
    return "run-" + _slug(trace_key)


def _plots(check: dict, goal: object, has_theta_d: bool) -> set[str]:
    """What to draw for each run of `check`: what the check declared (Check.plots, carried in the
    result); for a result written before checks declared them, what the run's data supports."""
    declared = check.get("plots")
    if isinstance(declared, list):
        return {p for p in declared if isinstance(p, str)}
    return {"trajectory", *(["heading"] if goal else ["angle"] if has_theta_d else [])}


def _run_views(check: dict, traces: dict, runs: list[dict], replays: str,
               hrefs: dict[str, str], shown: set[str], max_rows: int = REPLAY_ROWS) -> list[dict]:
    """The runs of one check; `shown` holds the trace keys an earlier check already shows (their replay
    is linked, not embedded again, and each section id stays unique in the page). Each run gets the
    plots the check declares (its `plots`: trajectory, heading, angle; states and signals by
    grader.report.signal_plots)."""
    from simiam.viewer.replay import TraceFormatError, render_replay

    views = []
    keys = _trace_keys(check, traces)
    if not keys:  # a check that measured a run another check kept (same goal): plot it, link the replay
        keys = _same_goal(check, traces)
    for k, key in enumerate(keys):
        shared = key in shown
        shown.add(key)
        trace = traces[key]
        if not isinstance(trace, dict):
            continue
        metrics = runs[k] if k < len(runs) else {}
        meta = trace.get("meta") or {}
        label = meta.get("check_label") or key
        steps = trace.get("steps") or {}
        anchor = run_anchor(key) + ("-in-" + _slug(str(check.get("id", ""))) if shared else "")
        view: dict[str, Any] = {"key": key, "label": label, "anchor": anchor, "problem": "",
                                "shared": None, "never_started": False,
                                "trajectory": None, "heading": None, "plots": [], "srcdoc": None,
                                "href": hrefs.get(key)}
        if len(steps.get("t") or []) < 2:  # row 0 is the start pose, before the first step
            view["never_started"] = True  # one line instead of an empty plot (the reason is in the message)
            views.append(view)
            continue
        goal = trace.get("goal") or metrics.get("goal")
        view["plots"] = declared_plots(check.get("plots"), trace)
        given = metrics.get("theta_d")
        theta_d = float(given) if isinstance(given, (int, float)) and math.isfinite(given) else None
        plots = _plots(check, goal, theta_d is not None)
        if "trajectory" in plots:
            view["trajectory"] = svg.trajectory_svg(trace)
        if "heading" in plots:
            view["heading"] = svg.heading_svg(trace, goal=goal, settle_time=metrics.get("settle_time"))
            view["heading_caption"] = "θ should enter the band and stay there"
        elif "angle" in plots and theta_d is not None:
            view["heading"] = svg.angle_svg(trace, theta_d)
            view["heading_caption"] = "θ should reach θ_d and stay there"
        if shared:
            view["shared"] = run_anchor(key)
            view["href"] = None
        elif replays == "inline" and not view["href"]:
            try:
                title = f"{check.get('id', '')}: {label}"
                view["srcdoc"] = render_replay(trace, title=title, max_rows=max_rows)
            except TraceFormatError as exc:
                view["problem"] = f"no replay: {exc}"
        views.append(view)
    return views


def _check_view(check: dict, traces: dict, replays: str, hrefs: dict[str, str], shown: set[str],
                max_rows: int = REPLAY_ROWS) -> dict:
    details = d if isinstance(d := check.get("details"), dict) else {}
    runs = _runs(details)
    listed = {"runs", "counterexample", "replay", "traces", "stdout", "stderr", "case"} | set(METRICS)
    extra = {k: v for k, v in details.items() if k not in listed}
    status = str(check.get("status", ""))
    views = _run_views(check, traces, runs, replays, hrefs, shown, max_rows)
    return {
        "id": str(check.get("id", "")), "name": str(check.get("name") or check.get("id", "")),
        "kind": str(check.get("kind", "")), "visibility": str(check.get("visibility", "") or ""),
        "status": status, "status_word": STATUS_WORDS.get(status, status or "?"),
        "points": check.get("points"), "max_points": check.get("max_points"),
        "message": str(check.get("message", "") or ""), "anchor": "check-" + _slug(str(check.get("id", ""))),
        "counterexample": _case_text(details["counterexample"]) if "counterexample" in details else None,
        "replay_command": str(details["replay"]) if details.get("replay") else "",
        "metrics": _metric_table(runs, [str(v["label"]) for v in views]),
        "output": [(name, str(details[name])) for name in ("stdout", "stderr") if details.get(name)],
        "extra": json.dumps(extra, indent=2, default=str, allow_nan=True) if extra else "",
        "runs": views,
    }


def _numerics(value: object) -> dict[str, str]:
    """The numeric environment line: the BLAS kernel that ran the student's code, and, where it is not
    official grading's, why and what that means (simiam.numerics)."""
    if not isinstance(value, dict):
        return {"numerics": "", "numerics_note": ""}
    kernel = str(value.get("kernel") or "unknown BLAS kernel")
    official = " (official grading's)" if value.get("official") is True else ""
    return {"numerics": f"{kernel}, {value.get('threads') or '?'} thread{official}",
            "numerics_note": str(value.get("note") or "")}


def _summary(result: dict, checks: list[dict]) -> dict:
    hidden = result.get("hidden")
    isolation = result.get("isolation") or result.get("sandbox") or result.get("sandbox_mode")
    if isinstance(isolation, dict):
        isolation = isolation.get("mode") or json.dumps(isolation)
    counts = {s: sum(1 for c in checks if c["status"] == s) for s in STATUS_WORDS}
    vary = hidden_variants(result.get("week"))  # what the week's hidden checks vary, in its own words
    if hidden:
        note = f"Official grading: the hidden variants ({vary}, drawn per seed) were run too."
    else:
        note = ("These are the visible checks. Official grading also runs hidden variants "
                f"({vary}, drawn per seed).")
    not_run = result.get("hidden_checks_not_run")
    if not hidden and isinstance(not_run, int) and not_run > 0:
        note = (f"{len(checks)} visible check{'s' if len(checks) != 1 else ''} ran here; "
                f"{not_run} hidden check{'s' if not_run != 1 else ''} "
                f"({vary}, drawn per seed) run at official grading.")
    problems = p if isinstance(p := result.get("problems"), dict) else {}
    notices = n if isinstance(n := result.get("notices"), list) else []
    return {"week": result.get("week"), "score": result.get("score"), "max_score": result.get("max_score"),
            "status": str(result.get("status", "")), "message": str(result.get("message", "") or ""),
            "seed": result.get("seed"), "grader_version": str(result.get("grader_version", "") or ""),
            "check_set_hash": str(result.get("check_set_hash", "") or ""),
            "submission": str(result.get("submission", "") or ""), "isolation": str(isolation or ""),
            "hidden": bool(hidden), "visibility_note": note, "counts": counts,
            "isolation_note": str(result.get("isolation_note", "") or ""),
            **_numerics(result.get("numerics")),
            "problems": [str(t) if str(t).startswith(str(f)) else f"{f}: {t}"
                         for f, v in problems.items() for t in (v if isinstance(v, list) else [v])],
            "notices": [str(n) for n in notices],
            "stdout": str(result.get("student_output") or result.get("stdout") or ""),
            "stderr": str(result.get("stderr", "") or "")}


def render_report(result: dict, traces: dict[str, dict] | None = None, *, replays: str = "inline",
                  replay_hrefs: dict[str, str] | None = None) -> str:
    """Return the HTML report for one submission's result JSON and its scenario traces.

    `replays`: "inline" embeds each run's replay page in an iframe `srcdoc` (self-contained; long runs
    thinned), "none" leaves them out; a trace key in `replay_hrefs` is linked to that URL instead.
    """
    if not isinstance(result, dict):
        raise TypeError(f"result must be the result JSON (a dict), not {type(result).__name__}")
    traces = traces or {}
    embedded = sum(1 for k in traces if k not in (replay_hrefs or {})) if replays == "inline" else 0
    max_rows = max(300, min(REPLAY_ROWS, REPORT_ROWS // max(1, embedded)))
    shown: set[str] = set()
    # failures first (the check that failed on a run also embeds its replay); passed ones after, collapsed
    checks = sorted((c for c in result.get("checks") or [] if isinstance(c, dict)),
                    key=lambda c: c.get("status") == "passed")
    views = [_check_view(c, traces, replays, replay_hrefs or {}, shown, max_rows) for c in checks]
    practice = _practice_view(result.get("practice"), traces, replays, replay_hrefs or {}, shown, max_rows)
    if any(run["srcdoc"] for view in views + (practice or {}).get("checks", []) for run in view["runs"]):
        from simiam.viewer.replay import content_security_policy

        csp = content_security_policy()  # the embedded replays inherit it: it must let their script run
    else:
        csp = STATIC_PAGE_CSP
    return _env().get_template("report.html.j2").render(summary=_summary(result, views), checks=views,
                                                        practice=practice, csp=csp)


def _practice_view(practice: object, traces: dict, replays: str, hrefs: dict[str, str], shown: set[str],
                   max_rows: int) -> dict | None:
    """`grade --practice`'s section: its note, the variants that ran, the practice checks (no points)."""
    if not isinstance(practice, dict):
        return None
    checks = sorted((c for c in practice.get("checks") or [] if isinstance(c, dict)),
                    key=lambda c: c.get("status") == "passed")
    views = []
    for c in checks:
        view = _check_view(c, traces, replays, hrefs, shown, max_rows)
        view["anchor"] = "practice-" + view["anchor"]
        views.append(view)
    variants = v if isinstance(v := practice.get("variants"), list) else []
    return {"note": str(practice.get("note", "") or ""), "about": str(practice.get("about", "") or ""),
            "variants": [json.dumps(v, sort_keys=True) for v in variants], "checks": views}


def render_report_pages(result: dict, traces: dict[str, dict] | None, *, folder: str,
                        assets: str) -> tuple[str, dict[str, str]]:
    """A report whose replays are pages of their own, as a batch writes it for each student: returns the
    report and its replay pages (file name -> HTML) to be written into `folder` (a URL relative to the
    report). The report draws its plots compact (grader.report.svg.compact_plots, with fewer points a
    line where the page would exceed PAGE_BYTES) and links each run's
    replay; each replay page loads the replay's script and styles from `assets` (a URL relative to the
    replay page: simiam.viewer.replay.shared_assets) and holds the rows the self-contained report would
    embed, so the same run plays."""
    from simiam.viewer.replay import TraceFormatError, render_replay

    traces = traces or {}
    max_rows = max(300, min(REPLAY_ROWS, REPORT_ROWS // max(1, len(traces))))
    pages: dict[str, str] = {}
    hrefs: dict[str, str] = {}
    for key, trace in traces.items():
        if not isinstance(trace, dict) or len((trace.get("steps") or {}).get("t") or []) < 2:
            continue  # no replay for a run that never started (the report says why)
        name = f"{_slug(key)}.html"
        if name in pages:  # two keys with one slug: the later one numbered
            name = f"{_slug(key)}-{len(pages)}.html"
        meta = trace.get("meta") or {}
        title = f"{key.split('#', 1)[0]}: {meta.get('check_label') or key}"
        try:
            pages[name] = render_replay(trace, title=title, max_rows=max_rows, assets=assets)
        except TraceFormatError:
            continue  # the report's run section has no replay link then
        hrefs[key] = f"{folder}/{name}"
    for points in PAGE_PLOT_POINTS:  # fewer points a line until the page fits its budget
        with svg.compact_plots(points):
            page = render_report(result, traces, replays="none", replay_hrefs=hrefs)
        if len(page.encode("utf-8", "replace")) <= PAGE_BYTES:
            break
    return page, pages


def write_report(result: dict, traces: dict[str, dict] | None, path: str | Path, *,
                 replays: str = "inline") -> Path:
    """Write the report to `path` and return it.

    replays="inline" (default) keeps the report one self-contained file (what the batch runner copies);
    replays="files" writes each run's full replay page into `<stem>-replays/` next to it and links them.
    """
    out = Path(path)
    hrefs: dict[str, str] = {}
    if replays == "files" and traces:
        from simiam.viewer.replay import TraceFormatError, write_replay

        folder = out.parent / f"{out.stem}-replays"
        for key, trace in traces.items():
            try:
                write_replay(trace, folder / f"{_slug(key)}.html")
            except TraceFormatError:
                continue
            hrefs[key] = f"{folder.name}/{_slug(key)}.html"
    page = render_report(result, traces, replays="none" if replays == "files" else replays,
                         replay_hrefs=hrefs)
    return safe_write.write_text(out, page, errors="replace")  # never through a link
