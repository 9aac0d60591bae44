"""Build a submission folder from a solution week plus the mistake of a wrong (or alternative) version."""

from __future__ import annotations

from pathlib import Path

import mistakes

ROOT = mistakes.ROOT


def week_of(name: str) -> int:
    """`week3_no_wrap` and `good_week3_other_gains` are week 3."""
    return int(name.removeprefix("good_").split("_")[0].removeprefix("week"))


def build(name: str, into: Path) -> Path:
    """solutions/weekN with tests/data/wrong/<name>.patch applied."""
    return mistakes.build("wrong", name, into, week_of(name))
