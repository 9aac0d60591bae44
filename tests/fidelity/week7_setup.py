"""Week 7 as the fidelity tests use it: the declared week (simiam/course/weeks/week7.py)."""

from __future__ import annotations

from simiam.course.weeks import get_week

WEEK7 = get_week(7)
