"""The late policy of a batch: a deadline, a penalty per day or hour, a cap, a grace period, extensions.

Computed as Canvas's late policy computes it (canvas-lms ``app/models/late_policy.rb``): the intervals
late are ``ceil(seconds late / interval)``, the deduction is ``rate x intervals`` percent of the points
possible, at most the cap (``--late-cap``, a share of the points possible) and, with ``--late-floor``,
never taking the score below that share (Canvas's "lowest possible grade": ``min(rate x intervals,
max(score% - floor%, 0))``). A submission no more than the grace period past its deadline is not late; one
past it is charged from the deadline. A per-student extension replaces the deadline. The score never goes
below 0, check points are never changed, and a student whose submission time is unknown is not charged
(the note says why): an ambiguity is never the student's loss.

The record is the shared convention's ``result["late"]``; ``result["score"]`` is the score after it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from datetime import datetime, timedelta, tzinfo

UNITS = {
    "s": 1,
    "sec": 1,
    "second": 1,
    "m": 60,
    "min": 60,
    "minute": 60,
    "h": 3600,
    "hour": 3600,
    "d": 86400,
    "day": 86400,
    "w": 604800,
    "week": 604800,
}
MAX_SECONDS = 10 * 365 * 86400  # ten years: anything longer is a typing error


class PolicyError(ValueError):
    """A late-policy option or roster cell that cannot be read (exit status 2 with this message)."""


@dataclass(frozen=True)
class LatePolicy:
    """What ``--deadline``, ``--late-penalty``, ``--late-cap``, ``--late-floor`` and ``--grace`` say."""

    deadline: datetime  # aware
    percent: float = 0.0  # of the points possible, per interval
    interval_s: int = 86400
    cap_percent: float | None = None
    floor_percent: float | None = None
    grace_s: int = 0

    def describe(self) -> str:
        """One line for the batch output and the summary."""
        unit = "day" if self.interval_s == 86400 else "hour"
        parts = [f"deadline {self.deadline.isoformat()}", f"{self.percent:g}% per {unit} late"]
        if self.grace_s:
            parts.append(f"grace {self.grace_s} s")
        if self.cap_percent is not None:
            parts.append(f"at most {self.cap_percent:g}%")
        if self.floor_percent is not None:
            parts.append(f"never below {self.floor_percent:g}% of the points")
        return ", ".join(parts)

    def to_json(self) -> dict:
        """For batch.json."""
        return {
            "deadline": self.deadline.isoformat(),
            "percent": self.percent,
            "interval_s": self.interval_s,
            "cap_percent": self.cap_percent,
            "floor_percent": self.floor_percent,
            "grace_s": self.grace_s,
        }


def parse_time(text: str, zone: tzinfo | None, what: str = "--deadline") -> datetime:
    """An ISO 8601 date and time; without an offset it is read in ``zone`` (``--timezone``), and with no
    zone either it is refused (a deadline an hour off charges a whole class)."""
    try:
        when = datetime.fromisoformat(text.strip().replace("Z", "+00:00"))
    except ValueError:
        raise PolicyError(
            f"{what} {text!r} is not an ISO 8601 date and time (2026-03-01T23:59:00-05:00)"
        ) from None
    if when.tzinfo is None:
        if zone is None:
            raise PolicyError(
                f"{what} {text!r} has no time zone: add one (2026-03-01T23:59-05:00, ...Z) or "
                f"give --timezone (America/New_York)"
            )
        when = when.replace(tzinfo=zone)
    return when


def parse_duration(text: str, what: str = "--grace") -> int:
    """``15m``, ``1h30m``, ``2d``, ``90s``, ``2 days`` -> seconds; a bare number is read as minutes for
    --grace (PolicyError otherwise)."""
    clean = text.strip().lower().replace(" ", "")
    if re.fullmatch(r"\d+(\.\d+)?", clean):
        return _bounded(float(clean) * 60, text, what)
    total = 0.0
    for number, unit in re.findall(r"(\d+(?:\.\d+)?)([a-z]+?)s?(?=\d|$)", clean):
        if unit not in UNITS:
            raise PolicyError(f"{what} {text!r}: unknown unit {unit!r} (s, m, h, d)")
        total += float(number) * UNITS[unit]
    if not re.fullmatch(r"(\d+(\.\d+)?[a-z]+)+", clean):
        raise PolicyError(f"{what} {text!r} is not a duration (15m, 1h30m, 2d)")
    return _bounded(total, text, what)


def _bounded(seconds: float, text: str, what: str) -> int:
    if not math.isfinite(seconds) or not 0 <= seconds <= MAX_SECONDS:
        raise PolicyError(f"{what} {text!r} is out of range (0 to ten years)")
    return int(round(seconds))


def parse_percent(text: str, what: str) -> float:
    """``50%`` or ``50`` -> 50.0, between 0 and 100 (PolicyError)."""
    try:
        value = float(text.strip().rstrip("%"))
    except ValueError:
        raise PolicyError(f"{what} {text!r} is not a percentage (50%)") from None
    if not math.isfinite(value) or not 0 <= value <= 100:
        raise PolicyError(f"{what} {text!r} must be between 0% and 100%")
    return value


def parse_penalty(text: str) -> tuple[float, int]:
    """``10%/day`` or ``2%/hour`` (also ``/d``, ``/h``) -> (percent per interval, interval in seconds)."""
    match = re.fullmatch(r"\s*([0-9.]+)\s*%?\s*/\s*(d|day|h|hr|hour)s?\s*", text.lower())
    if match is None:
        raise PolicyError(f"--late-penalty {text!r}: write it as 10%/day or 2%/hour")
    return parse_percent(match[1], "--late-penalty"), 86400 if match[2].startswith("d") else 3600


def parse_extension(text: str, deadline: datetime, zone: tzinfo | None) -> datetime | None:
    """A roster's extension cell: a new deadline (ISO 8601), or extra time (``2d``, ``36h``, a bare number
    of days); "" means none (PolicyError naming the cell)."""
    text = text.strip()
    if not text:
        return None
    if re.fullmatch(r"\d+(\.\d+)?", text):
        return deadline + timedelta(seconds=_bounded(float(text) * 86400, text, "extension"))
    if re.fullmatch(r"[0-9.]+\s*[a-zA-Z ]+", text):
        return deadline + timedelta(seconds=parse_duration(text, "extension"))
    return parse_time(text, zone or deadline.tzinfo, "extension")


def late_record(
    policy: LatePolicy,
    submitted_at: str,
    extension_until: datetime | None,
    score: float,
    max_score: float | None,
    late_flag: bool = False,
    platform: str = "",
) -> dict:
    """``result["late"]`` for one graded student (see the module docstring for the rule)."""
    due = extension_until or policy.deadline
    record = {
        "deadline": policy.deadline.isoformat(),
        "submitted_at": submitted_at,
        "seconds_late": 0,
        "extension_until": extension_until.isoformat() if extension_until else None,
        "penalty_percent": 0.0,
        "penalty_points": 0.0,
        "score_before": score,
        "note": "",
    }
    when = _aware(submitted_at)
    if when is None:
        record["submitted_at"] = ""
        record["note"] = (
            "marked late by Canvas, no submission time: give --times"
            if late_flag
            else f"no submission time from {platform or 'the submission'}: no penalty (give --times)"
        )
        return record
    seconds = (when - due).total_seconds()
    record["seconds_late"] = max(0, math.ceil(seconds))
    if seconds <= 0:
        record["note"] = "on time" + (" (extension)" if extension_until else "")
        return record
    if seconds <= policy.grace_s:
        record["note"] = "within the grace period: no penalty"
        return record
    intervals = math.ceil(seconds / policy.interval_s)
    percent = policy.percent * intervals
    if policy.cap_percent is not None:
        percent = min(percent, policy.cap_percent)
    if policy.floor_percent is not None and max_score:
        percent = min(percent, max(100.0 * score / max_score - policy.floor_percent, 0.0))
    percent = min(percent, 100.0)
    points = min(score, (max_score or 0.0) * percent / 100.0)
    unit = "day" if policy.interval_s == 86400 else "hour"
    record.update(
        penalty_percent=round(percent, 6),
        penalty_points=round(points, 6),
        note=f"{intervals} {unit}{'s' if intervals != 1 else ''} late",
    )
    return record


def _aware(text: str) -> datetime | None:
    try:
        when = datetime.fromisoformat(text)
    except (TypeError, ValueError):
        return None
    return when if when.tzinfo is not None else None
