"""The grading function a batch runs in each grading process: one task in, one outcome out.

A task is a plain dict, the same for the local pool and for Dask workers on other machines::

    {"student": "alice", "display": "alice.zip", "week": 3, "seed": 1234, "hidden": true,
     "sandbox": "auto", "grader": "<fingerprint>", "check_grader": false,
     "files": {"go_to_goal.py": "<base64>", ...}, "notices": ["notes.txt: ... skipped"] (optional)}

The submission travels as its bytes (hashed by the runner), so a remote worker needs no shared disk and
grades exactly what was hashed. ``check_grader`` (set for Dask) makes a grading machine whose installed
grader differs from the runner's refuse the task, so a stale worker cannot mix versions.
The outcome is ``{"result": <result JSON>, "html": <report> | None, "replays": {<file name>: <page>}}``
(grader.batch.pages).
"""

from __future__ import annotations

import functools
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from grader.batch.cache import grader_fingerprint
from grader.batch.grading_process import overlapped
from grader.batch.names import student_stem
from grader.batch.pages import ASSETS_FROM_REPLAY, replay_folder
from grader.batch.submissions import unpack
from grader.grading import grade_submission  # at import: a grading process loads it before its first task
from simiam.course.weeks import get_week


class GraderMismatch(RuntimeError):
    """The grading process runs different grader code than the batch runner (a stale Dask worker)."""


def grade_first(task: dict) -> Callable[[], dict]:
    """Grade one submission with :func:`grader.grading.grade_submission` (the seam every front door uses);
    returns the second phase, which writes the HTML report and gives the outcome.

    The student's worker is closed and their temporary copy deleted before this returns, so the second
    phase only turns plain data into a page: a grading process may run it while the next submission's
    worker starts (grader.batch.grading_process).
    """
    expected = task.get("grader")
    if task.get("check_grader") and expected != (mine := grader_fingerprint()):
        raise GraderMismatch(f"this grading machine runs grader {mine}, the batch expects {expected}; "
                             f"install the same version everywhere")
    week = int(task["week"])
    course_files = get_week(str(week)).student_files
    if not any(name in course_files for name in task["files"]):
        # nothing of the week's to grade: the student sent the wrong files, not a zero-point attempt
        result = {"week": week, "score": 0.0, "max_score": None, "status": "invalid", "seed": task["seed"],
                  "hidden": bool(task["hidden"]), "grader_version": expected, "checks": [],
                  "submission": task.get("display") or task["student"],
                  "message": f"the submission holds none of week {week}'s files ({', '.join(course_files)}); "
                             f"it has: {', '.join(sorted(task['files'])[:10])}",
                  "notices": [n for n in task.get("notices") or [] if isinstance(n, str)]}
        return functools.partial(lambda r: {"result": r, "html": None}, result)
    with tempfile.TemporaryDirectory(prefix="simiam-batch-") as tmp:
        submission = unpack(task["files"], Path(tmp) / "submission")
        began = time.monotonic()
        traces: dict[str, dict] = {}
        result = grade_submission(week=week, submission=submission, seed=int(task["seed"]),
                                  hidden=bool(task["hidden"]), sandbox=task.get("sandbox", "auto"),
                                  # what the student types at home to replay a failing case: their own
                                  # ./assignments/weekN, not the batch's temporary folder
                                  replay_prefix=f"grade week{week}", traces=traces)
    # What the runner left out of the submission (a file it could not name) is said beside the grading's
    # own notices, in the report too.
    result["notices"] = [*(n for n in task.get("notices") or [] if isinstance(n, str)),
                         *(result.get("notices") or [])]
    # The temporary path differs on every run and machine; the student's own name does not. It is
    # replaced in the result's plain text, before the report renders (and escapes) it: never in HTML.
    renamed = replace_text(result, str(submission), task.get("display") or task["student"])
    assert isinstance(renamed, dict)  # replace_text keeps the shape of what it is given
    if isinstance(expected, str) and expected:
        # One version string in every file of a batch: the batch's grader fingerprint (what decides a
        # regrade), before the report shows it. The check set's own hash stays in `check_set_hash`.
        renamed["grader_version"] = expected
    return functools.partial(_with_report, renamed, traces, began, student_stem(str(task["student"])))


def _with_report(result: dict, traces: dict[str, dict], began: float, stem: str) -> dict:
    """The outcome: the result, its HTML report (None where the report package is not installed) and the
    report's replay pages (grader.batch.pages: written under replays/<stem>/, sharing assets/)."""
    timing = tm if isinstance(tm := result.get("timing"), dict) else {}
    try:
        from grader.report.html import render_report_pages
    except ImportError:  # a grader installed without its report package: the batch writes a plain page
        html: str | None = None
        replays: dict[str, str] = {}
    else:
        html, replays = render_report_pages(result, traces, folder=replay_folder(stem),
                                            assets=ASSETS_FROM_REPLAY)
    # the whole call, report writing included: what the batch adds is measured against this
    result["timing"] = {**timing, "grade_submission_seconds": round(time.monotonic() - began, 3)}
    return {"result": result, "html": html, "replays": replays}


@overlapped(grade_first)
def grade_task(task: dict) -> dict:
    """Grade one submission and write its report: ``{"result": <result JSON>, "html": <page> | None,
    "replays": {<file name>: <replay page>}}``."""
    return grade_first(task)()


def replace_text(value: object, old: str, new: str) -> object:
    """``value`` with ``old`` replaced by ``new`` in every string inside it (keys included)."""
    if isinstance(value, str):
        return value.replace(old, new)
    if isinstance(value, list):
        return [replace_text(v, old, new) for v in value]
    if isinstance(value, dict):
        return {replace_text(k, old, new): replace_text(v, old, new) for k, v in value.items()}
    return value
