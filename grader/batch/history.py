"""Every earlier grading of a student, kept, and what changed since the last one.

A student's result is replaced when they are graded again (a new submission, grader, seed or hidden set,
a late policy, ``--only``, ``--force``). The result it replaces is first copied to
``history/<stem>/<timing.graded_at>.json`` (the per-student HTML is not kept: at ~0.6 MB a page it would
double the folder at every regrade, and the JSON holds every score, check and message). The new
result records ``batch.change``: the score and status before and after and why they were graded again,
which ``batch.json`` and the summary list for the students whose score or status changed.
"""

from __future__ import annotations

import json
import math
import re
from datetime import datetime, timezone
from pathlib import Path

from grader.batch.store import read_json, write_json

HISTORY = "history"
_STAMP = re.compile(r"\A\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(?:\.\d+)?(?:Z|[+-]\d\d:\d\d)\Z")
REASONS = ("new submission", "new grader", "new seed", "new hidden set", "hidden checks", "late policy",
           "regrade asked with --only", "regrade asked with --force")


def archive(out: Path, stem: str, stored: dict) -> str:
    """Copy ``stored`` (the result about to be replaced) into ``history/<stem>/``; returns its path
    relative to ``out``. The same grading archived twice (a result moved to superseded/, then replaced)
    is kept once."""
    batch = b if isinstance(b := stored.get("batch"), dict) else {}
    timing = t if isinstance(t := stored.get("timing"), dict) else {}
    when = timing.get("graded_at")
    name = (when.replace(":", "-") if isinstance(when, str) and _STAMP.match(when) else "undated")
    key = batch.get("cache_key")
    if isinstance(key, str) and re.fullmatch(r"[0-9a-f]{8,64}", key):
        name += "-" + key[:8]
    folder = out / HISTORY / stem
    clean = _finite(stored)
    text = json.dumps(clean, sort_keys=True)
    for n in range(1000):
        path = folder / (f"{name}.json" if n == 0 else f"{name}-{n}.json")
        existing = read_json(path)
        if existing is None and not path.exists():
            write_json(path, clean)
            return path.relative_to(out).as_posix()
        if existing is not None and json.dumps(existing, sort_keys=True) == text:
            return path.relative_to(out).as_posix()
    raise OSError(f"{folder}: too many earlier gradings with one date")


def reasons(old: dict, new: dict, asked: str | None = None) -> list[str]:
    """Why ``new`` differs from ``old``, the earlier result of the same student, in REASONS' words;
    ``asked`` is "only" or "force" when the command asked for the regrade."""
    ob = b if isinstance(b := old.get("batch"), dict) else {}
    nb = b if isinstance(b := new.get("batch"), dict) else {}
    found = []
    if ob.get("submission_sha256") != nb.get("submission_sha256"):
        found.append("new submission")
    if ob.get("grader") != nb.get("grader"):
        found.append("new grader")
    if old.get("seed") != new.get("seed"):
        found.append("new seed")
    elif _digest(ob) != _digest(nb):
        found.append("new hidden set")
    if bool(old.get("hidden")) != bool(new.get("hidden")):
        found.append("hidden checks")
    if _late(old) != _late(new):
        found.append("late policy")
    if asked in ("only", "force"):
        found.append(f"regrade asked with --{asked}")
    return found


def change(old: dict | None, new: dict, kept: str | None, asked: str | None = None) -> dict | None:
    """``batch.change`` of ``new``: None for a first grading; else the score and status before and after,
    the reasons (:func:`reasons`), where the earlier result is kept and when (``at``, UTC)."""
    if old is None:
        return None
    return {"score_before": _score(old), "score_after": _score(new), "status_before": old.get("status"),
            "status_after": new.get("status"), "reasons": reasons(old, new, asked), "history": kept,
            "at": datetime.now(timezone.utc).isoformat()}


def changed_rows(results: dict[str, dict], since: datetime | None = None) -> list[dict]:
    """The students whose score or status changed at their last grading: ``[{"student", "before",
    "after", "status_before", "status_after", "reasons", "at", "this_run"}]``, for batch.json and the
    summary. ``this_run``: the change was made at or after ``since`` (a regrade, or a late policy applied
    again, by this run); those come first, so an instructor tells this run's changes from earlier ones."""
    rows = []
    for sid, result in sorted(results.items()):
        batch = b if isinstance(b := result.get("batch"), dict) else {}
        record = batch.get("change")
        if not isinstance(record, dict):
            continue
        before, after = record.get("score_before"), record.get("score_after")
        if before == after and record.get("status_before") == record.get("status_after"):
            continue
        words = record.get("reasons")
        at = _when(record.get("at"))
        rows.append({"student": sid, "before": before, "after": after,
                     "status_before": str(record.get("status_before"))[:20],
                     "status_after": str(record.get("status_after"))[:20],
                     "reasons": [w for w in words if w in REASONS] if isinstance(words, list) else [],
                     "at": at.isoformat() if at else "",
                     "this_run": bool(at and since and at >= since)})
    rows.sort(key=lambda row: not row["this_run"])     # stable: by student within each part
    return rows


def _when(value: object) -> datetime | None:
    """A change's ``at`` read back (a stored result is checked, never trusted): an aware time, else None."""
    if not isinstance(value, str) or not _STAMP.match(value):
        return None
    try:
        when = datetime.fromisoformat(value.replace("Z", "+00:00"))
    except ValueError:
        return None
    return when if when.tzinfo is not None else None


def _finite(value: object) -> object:
    """``value`` with every NaN or infinity (which Python's JSON reader accepts) replaced by None."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, list):
        return [_finite(v) for v in value]
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    return value


def _score(result: dict) -> float | None:
    """A stored score, or None when it is not a finite number (a stored result is read back as data)."""
    score = result.get("score")
    if isinstance(score, bool) or not isinstance(score, (int, float)) or not math.isfinite(score):
        return None
    return float(score)


def _digest(batch: dict) -> object:
    hidden_set = batch.get("hidden_set")
    return hidden_set.get("digest") if isinstance(hidden_set, dict) else None


def _late(result: dict) -> object:
    late = result.get("late")
    if not isinstance(late, dict):
        return None
    return (late.get("penalty_percent"), late.get("penalty_points"), late.get("deadline"),
            late.get("extension_until"))
