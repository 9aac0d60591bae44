"""The late policy laid over stored results and pages, without running any student code again.

A student's ``score_before`` is kept in ``result["late"]``, so a changed policy (another deadline, rate,
cap or extension) is re-applied to the stored result on the next run, and the short "Late submission"
section of their page is replaced. That section sits right after the page's ``<body>`` tag, between two
comments: student text on the page is escaped, and the section is looked for only at that one place, so
nothing a student writes can pass for it or move it.
"""

from __future__ import annotations

import html
import math
import re
from datetime import datetime

from grader.batch.identity import Identity
from grader.batch.late import LatePolicy, late_record

START, END = "<!-- simiam:late -->", "<!-- /simiam:late -->"
_BODY = re.compile(r"<body\b[^>]*>", re.IGNORECASE)


def _number(value: object) -> float | None:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    return float(value) if ok else None  # type: ignore[arg-type]


def raw_score(result: dict) -> float | None:
    """The score before any late penalty; None when a stored result's numbers do not hold together (then
    the student is graded again rather than charged from a forged or damaged file)."""
    late = result.get("late")
    score = (
        _number(late.get("score_before"))
        if isinstance(late, dict)
        else _number(result.get("score"))
        if late is None
        else None
    )
    top = _number(result.get("max_score"))
    if score is None or score < 0 or (top is not None and score > top + 1e-9):
        return None
    return score


def settle_late(
    result: dict, identity: Identity, policy: LatePolicy | None, extension: datetime | None
) -> bool | None:
    """Set ``result["late"]`` and ``result["score"]`` for ``policy`` (no record without one). True when
    the result changed, False when it already held this, None when its stored numbers cannot be trusted."""
    if result.get("status") != "graded":
        return False
    raw = raw_score(result)
    if raw is None:
        return None
    new = (
        late_record(
            policy,
            identity.submitted_at,
            extension,
            raw,
            _number(result.get("max_score")),
            identity.late_flag,
            identity.platform,
        )
        if policy
        else None
    )
    if new == result.get("late") and (new is not None or _number(result.get("score")) == raw):
        return False
    if new is None:
        result.pop("late", None)
        result["score"] = raw
    else:
        result["late"] = new
        result["score"] = round(raw - float(new["penalty_points"]), 6)
    return True


def with_late_section(page: str, late: dict | None) -> str:
    """``page`` with its late section replaced by one for ``late`` (removed when nothing is charged)."""
    body = _BODY.search(page)
    at = body.end() if body else 0
    rest = page[at:]
    if rest.startswith(START) and (end := rest.find(END)) >= 0:
        rest = rest[end + len(END) :]
    return page[:at] + _section(late) + rest


def _section(late: dict | None) -> str:
    if not isinstance(late, dict) or not (late.get("seconds_late") or late.get("penalty_points")):
        return ""
    points = float(late.get("penalty_points") or 0.0)
    before = float(late.get("score_before") or 0.0)
    due = late.get("extension_until") or late.get("deadline")
    text = (
        f"Submitted {late.get('submitted_at')}; due {due}"
        f"{' (your extension)' if late.get('extension_until') else ''}: {late.get('note')}. "
    )
    text += (
        f"Late penalty: {points:g} point{'' if points == 1 else 's'} "
        f"({float(late.get('penalty_percent') or 0):g}% of the points "
        f"possible); score {before:g} before the penalty, {before - points:g} after it."
        if points
        else "No penalty."
    )
    return (
        f'{START}<section id="late-policy" style="border:2px solid #c80;padding:2px 12px;margin:8px 0">'
        f"<h2>Late submission</h2><p>{html.escape(text)}</p></section>{END}"
    )
