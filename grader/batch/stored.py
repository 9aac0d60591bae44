"""Whether a per-student result read back from the output folder has the shape the batch relies on.

The ``<stem>.json`` files of an output folder are read again on every rerun: to skip a student already
graded (grader.batch.cache.is_fresh) and to rebuild the class files (gradebook, exports, summary.html) from
them. Anyone who can write that folder can edit them, and a half-copied folder can hold anything, so a stored
result is data to check, not to trust: one with a valid cache key and ``"points": "abc"`` once stopped a
resumed batch in summary.py (issue 30 item 6). `problem` is the one cheap check every reader uses: a result
it finds fault with is regraded by the runner and left out of the class files until it is, never read.

What it checks is what the class files compute with: the status a text, the score
and maximum finite numbers (or null where a crashed grading has none), every check a dict with text id and
status and finite points, the batch record a dict, and a late-policy record (when present) with finite
figures. Text fields other readers show are bounded where they are shown, not here.
"""

from __future__ import annotations

import math
from typing import Any, TypeGuard

MAX_CHECKS = 1000  # a week has at most some 40 checks; more is not a result of this grader


def _number(value: Any) -> bool:
    return type(value) in (int, float) and math.isfinite(value)


def _problem_of_check(check: Any, i: int) -> str | None:
    if not isinstance(check, dict):
        return f"check {i + 1} is not an object"
    for key in ("id", "status"):
        if not isinstance(check.get(key), str):
            return f"check {i + 1} has no text {key}"
    for key in ("points", "max_points"):
        if key in check and not _number(check[key]):
            return f"check {check['id'][:80]!r} has {key} that are not a finite number"
    if "details" in check and not isinstance(check["details"], dict):
        return f"check {check['id'][:80]!r} has details that are not an object"
    return None


def problem(result: Any) -> str | None:
    """Why a stored result cannot be reused as it is (in words for the instructor), or None if it can."""
    if not isinstance(result, dict):
        return "not a JSON object"
    if not isinstance(result.get("status"), str):
        return "no text status"
    for key in ("score", "max_score"):
        value = result.get(key)
        if value is not None and not _number(value):
            return f"{key} is not a finite number"
    checks = result.get("checks", [])
    if not isinstance(checks, list) or len(checks) > MAX_CHECKS:
        return "checks is not a list of checks"
    for i, check in enumerate(checks):
        why = _problem_of_check(check, i)
        if why:
            return why
    for key in ("batch", "timing", "late"):
        if key in result and not isinstance(result[key], dict):
            return f"{key} is not an object"
    late = result.get("late") or {}
    for key in ("seconds_late", "penalty_percent", "penalty_points", "score_before"):
        if key in late and not _number(late[key]):
            return f"late.{key} is not a finite number"
    return None


def well_formed(result: Any) -> TypeGuard[dict]:
    """True if `problem` finds nothing wrong with a stored result."""
    return problem(result) is None
