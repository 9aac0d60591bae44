"""Wrong versions the intake and late-policy tests must catch (each test proves it can fail on one)."""

from __future__ import annotations

import math
import re

# Canvas's entry name read without its LATE marker: "smithjohn_LATE_102_..." keeps LATE in the name and
# the student is never reported as marked late.
CANVAS_ENTRY_IGNORING_LATE = re.compile(
    r"^(?:(?P<name>[^/]*?)_)??(?P<late>(?!))?(?P<uid>anon_[0-9a-z]+|\d+)_"
    r"(?:(?P<att>\d+)_(?P<file>[^/]+)|(?P<kind>text|link)\.html)$",
    re.IGNORECASE,
)

# Canvas's entry name with a case-sensitive LATE (older Canvas wrote "late").
CANVAS_ENTRY_UPPER_LATE_ONLY = re.compile(
    r"^(?:(?P<name>[^/]*?)_)??(?:(?P<late>LATE)_)?"
    r"(?P<uid>anon_[0-9a-zA-Z]+|\d+)_"
    r"(?:(?P<att>\d+)_(?P<file>[^/]+)|(?P<kind>text|link)\.html)$"
)


def penalty_percent_floor(
    seconds_late: float, rate: float, interval_s: int, cap: float | None, grace_s: int
) -> float:
    """Counts whole intervals only (floor): 26 hours late is charged one day, not two."""
    if seconds_late <= grace_s:
        return 0.0
    percent = rate * math.floor(seconds_late / interval_s)
    return min(percent, cap) if cap is not None else percent


def penalty_percent_no_cap(
    seconds_late: float, rate: float, interval_s: int, cap: float | None, grace_s: int
) -> float:
    """Forgets the cap."""
    if seconds_late <= grace_s:
        return 0.0
    return rate * math.ceil(seconds_late / interval_s)


def penalty_percent_grace_shifts(
    seconds_late: float, rate: float, interval_s: int, cap: float | None, grace_s: int
) -> float:
    """Counts from the end of the grace period: 24 h 10 min late with 15 min grace is charged one day."""
    if seconds_late <= grace_s:
        return 0.0
    percent = rate * math.ceil((seconds_late - grace_s) / interval_s)
    return min(percent, cap) if cap is not None else percent


def penalty_percent_no_grace(
    seconds_late: float, rate: float, interval_s: int, cap: float | None, grace_s: int
) -> float:
    """Ignores the grace period: ten minutes late is a whole day's penalty."""
    if seconds_late <= 0:
        return 0.0
    percent = rate * math.ceil(seconds_late / interval_s)
    return min(percent, cap) if cap is not None else percent
