"""The grade a course platform is given for one student, and the student's identity, from a stored result.

The same rules for every platform import (Canvas, Moodle), so that they never disagree:

- ``graded``: the result's ``score``, which is after any late penalty (``result["late"]``);
- ``invalid``: ``0``. The student handed in something that could not be graded as submitted (a broken zip,
  no course file); it earned 0 points and their report says why, as ``gradebook.csv`` does. An instructor
  who means to let such a student resubmit changes that cell;
- ``held`` (a problem on the instructor's side), ``timeout`` and ``crashed`` (the grading did not
  finish: a rerun retries it), a roster student with no submission, and a stored score that is not a
  finite number from 0 to the week's maximum: blank, with the reason in the export's record
  (``batch.json`` under ``exports``). A blank is never an invented 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from grader.batch.identity import Identity

MAX_LISTED = 200        # students named per list in batch.json's ``exports`` (the count says the rest)


def listed(name: str, why: dict[str, str]) -> dict:
    """``{name: first MAX_LISTED of why, name + "_count": len(why)}`` for batch.json."""
    return {name: dict(list(why.items())[:MAX_LISTED]), f"{name}_count": len(why)}


@dataclass(frozen=True)
class Posted:
    """What one student's row says: their identity, the grade ("" for blank) and why it is blank."""

    identity: Identity
    grade: str
    why_blank: str = ""
    result: dict | None = None


def identity_of(sid: str, result: dict | None) -> Identity:
    """The identity stored with a result (``batch.identity``), else one holding only the student id."""
    batch = result.get("batch") if isinstance(result, dict) else None
    stored = Identity.from_json(batch.get("identity")) if isinstance(batch, dict) else None
    return stored if stored is not None else Identity(id=sid)


def points(value: float) -> str:
    """A score as a platform reads it: plain decimal, at most 4 places, no exponent (``8.5``, ``10``)."""
    text = f"{round(value, 4):.4f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def posted(sid: str, result: dict | None, max_score: float | None) -> Posted:
    """The grade to post for student ``sid`` (``result`` None: on the roster, nothing submitted)."""
    identity = identity_of(sid, result)
    if result is None:
        return Posted(identity, "", "on the roster, no submission")
    status = result.get("status")
    if status == "invalid":
        return Posted(identity, "0", result=result)
    if status != "graded":
        why = {"held": "held: a problem on the instructor's side (see its message)",
               "timeout": "timeout: the grading did not finish (rerun to retry)",
               "crashed": "crashed: the grading did not finish (rerun to retry)"}
        return Posted(identity, "", why.get(str(status), f"status {str(status)[:20]!r}"), result)
    score = result.get("score")
    top = max_score if max_score is not None else math.inf
    if (isinstance(score, bool) or not isinstance(score, (int, float)) or not math.isfinite(score)
            or not 0 <= score <= top + 1e-9):
        return Posted(identity, "", "the stored score is not a number from 0 to the maximum", result)
    return Posted(identity, points(float(score)), result=result)


def class_rows(results: dict[str, dict], max_score: float | None, roster: list[Identity] | None = None,
               missing: list[str] | None = None) -> list[Posted]:
    """One :class:`Posted` per student with a result, then one per roster student in ``missing`` (with a
    blank grade), ordered by student id."""
    rows = {sid: posted(sid, result, max_score) for sid, result in results.items()}
    by_id = {r.id: r for r in roster or []}
    for sid in missing or []:
        if sid not in rows:
            row = posted(sid, None, max_score)
            rows[sid] = Posted(by_id.get(sid, row.identity), "", row.why_blank)
    return [rows[sid] for sid in sorted(rows)]
