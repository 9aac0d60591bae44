"""Class-level files built from the per-student results: ``gradebook.csv``, the Gradescope export, and
the grades and reports back into Canvas (grader.batch.canvas_export) and Moodle
(grader.batch.moodle_export), all by the same rules (grader.batch.posted).

All are rebuilt from the stored ``<id>.json`` files at the end of every run (including a resumed or
interrupted one), so they always agree with the per-student results on disk.
"""

from __future__ import annotations

import csv
import io
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from grader.batch.canvas_export import write_canvas
from grader.batch.identity import Identity
from grader.batch.moodle_export import write_moodle
from grader.batch.posted import class_rows
from grader.batch.store import output_folder, write_atomic, write_json

GRADESCOPE_VISIBILITY = ("visible", "hidden", "after_due_date", "after_published")
DEFAULT_CANVAS_TITLE = "Autograder"        # with the week: "Autograder week 3" (--canvas-assignment)
WITH_REPORT = ("graded", "invalid")        # statuses whose report goes back to the student


def check_ids(results: dict[str, dict]) -> list[str]:
    """Every check id in the class, in the order the grader declares them (first graded result first)."""
    ids: list[str] = []
    seen: set[str] = set()
    for sid in sorted(results):
        for check in results[sid].get("checks") or []:
            cid = check.get("id") if isinstance(check, dict) else None
            if isinstance(cid, str) and cid not in seen:
                seen.add(cid)
                ids.append(cid)
    return ids


def class_max_score(results: dict[str, dict]) -> float | None:
    """The week's maximum, from any graded result (a timed-out student's result has none of its own)."""
    for result in results.values():
        if result.get("status") == "graded" and isinstance(result.get("max_score"), (int, float)):
            return float(result["max_score"])
    return None


def safe_cell(value: object) -> object:
    """A CSV cell a spreadsheet will not run: text starting with = + - @ (a formula) gets a quote."""
    if isinstance(value, str) and value[:1] in ("=", "+", "-", "@", "\t", "\r"):
        return "'" + value
    return value


def gradebook_csv(results: dict[str, dict], missing: list[str] | tuple[str, ...] = ()) -> str:
    """One row per student: id, one column of points per check, total (after any late penalty), max,
    status, message, late_penalty and score_before_penalty (blank without a late policy), and the grader
    version that graded it (the batch's one version string); a ``held`` student's total is blank, and
    each roster student in ``missing`` has a row with a blank total."""
    ids = check_ids(results)
    fallback_max = class_max_score(results)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["student", *ids, "total", "max", "status", "message", "late_penalty",
                     "score_before_penalty", "grader"])
    for sid in sorted(results):
        result = results[sid]
        points = {c.get("id"): c.get("points") for c in result.get("checks") or [] if isinstance(c, dict)}
        max_score = result.get("max_score")
        if not isinstance(max_score, (int, float)):
            max_score = fallback_max
        late = lt if isinstance(lt := result.get("late"), dict) else {}
        row = [sid, *[_number(points.get(cid)) for cid in ids], _number(result.get("score", 0.0)),
               _number(max_score), result.get("status", ""), _one_line(result.get("message", "")),
               _number(late.get("penalty_points")), _number(late.get("score_before")),
               _one_line(result.get("grader_version", ""), 100)]
        writer.writerow([safe_cell(cell) for cell in row])
    for sid in sorted(set(missing) - set(results)):
        writer.writerow([safe_cell(c) for c in [sid, *[""] * len(ids), "", _number(fallback_max), "missing",
                                                 "on the roster, no submission", "", "", ""]])
    return buffer.getvalue()


def _number(value: object) -> float | str:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return ""
    return round(float(value), 6)


def _one_line(text: object, limit: int = 1000) -> str:
    """One line of at most ``limit`` characters: a gradebook row stays small whatever a message holds."""
    line = " ".join(str(text or "").split())
    return line if len(line) <= limit else line[:limit] + " [...]"


def gradescope_result(result: dict) -> dict:
    """A Gradescope autograder ``results.json`` for one student's result."""
    tests = []
    for check in result.get("checks") or []:
        if not isinstance(check, dict):
            continue
        visibility = check.get("visibility")
        if visibility not in GRADESCOPE_VISIBILITY:
            visibility = "after_due_date" if check.get("hidden") else "visible"
        name = check.get("name") or check.get("id") or "check"
        output = str(check.get("message") or "")
        if check.get("status") in ("error", "timeout"):
            output = f"[{check['status']}] {output}".strip()
        if check.get("printed"):   # a hidden check's: shown in this test only, with its visibility
            output += f"\n\nWhat your code printed during this check:\n{check['printed']}"
        tests.append({"name": f"{check.get('id')}: {name}" if check.get("id") else name,
                      "score": float(_number(check.get("points")) or 0.0),
                      "max_score": float(_number(check.get("max_points")) or 0.0),
                      "status": "passed" if check.get("status") == "passed" else "failed",
                      "output": output, "visibility": visibility})
    score = _number(result.get("score"))
    # every text Gradescope shows is plain text: student text (names, messages quoting their output) is
    # never read as HTML, Markdown or ANSI colour by the page that shows it
    export = {"score": float(score) if score != "" else 0.0, "tests": tests,
              "visibility": "visible", "stdout_visibility": "hidden", "output_format": "text",
              "test_output_format": "text", "test_name_format": "text"}
    if result.get("status") != "graded" or result.get("message"):
        export["output"] = f"{result.get('status', 'crashed')}: {result.get('message') or ''}".strip(": ")
    return export


def write_exports(out: Path, results: dict[str, dict], stems: dict[str, str], meta: dict | None = None, *,
                  week: int | None = None, title: str = DEFAULT_CANVAS_TITLE,
                  roster: list[Identity] | None = None, missing: list[str] | None = None) -> dict:
    """Write ``gradebook.csv``, ``gradescope/<id>/results.json`` for every student in ``results``, and the
    Canvas and Moodle files (with a blank row for each roster student in ``missing``); returns what the
    platform files left blank or out, and why, for ``batch.json``. ``roster`` and ``missing`` default to
    the run's ``meta["roster"]`` (Identity JSON) and ``meta["missing"]``.

    The Gradescope files are written by a few threads: each write waits for its fsync, and at the end of
    a batch the cores have nothing else to do (400 students: 5.3-6.7 s one by one, 1.9-3.4 s so).
    No level below ``out`` is followed if it is a link (grader.batch.store.output_folder)."""
    meta = meta or {}
    if missing is None:
        missing = [m for m in meta.get("missing") or [] if isinstance(m, str)]
    if roster is None:
        roster = [i for i in map(Identity.from_json, meta.get("roster") or []) if i is not None]
    with output_folder(out):
        write_atomic(out / "gradebook.csv", gradebook_csv(results, missing))
        max_score = class_max_score(results)
        rows = class_rows(results, max_score, roster, missing)
        pages = {sid: out / f"{stems[sid]}.html" for sid, r in results.items()
                 if r.get("status") in WITH_REPORT}
        if title == DEFAULT_CANVAS_TITLE and week is not None:
            title = f"{DEFAULT_CANVAS_TITLE} week {week}"
        record = {**write_canvas(out, rows, pages, title, max_score),
                  **write_moodle(out, rows, pages, title, max_score)}

        def export(sid: str) -> None:
            write_json(out / "gradescope" / stems[sid] / "results.json", gradescope_result(results[sid]))
        with ThreadPoolExecutor(max_workers=8, thread_name_prefix="gradescope-export") as writers:
            list(writers.map(export, results))      # list(): the first error is raised here
    return record
