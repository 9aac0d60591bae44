"""Wrong: week 3 declared without its ensure_w block (its checks still probe QBSupervisor.ensure_w)."""

from dataclasses import replace

from simiam.course.weeks.week3 import WEEK as DECLARED

WEEK = replace(DECLARED, blocks=tuple(b for b in DECLARED.blocks if b.scope != "QBSupervisor.ensure_w"))
