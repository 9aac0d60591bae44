"""The colour of a state (or label) name, one function for every page: the grader's report and the replay
(which receives each name's colour in its data instead of hashing names in its own script, so that the two
can never disagree again, as they did: the report hashed with CRC-32, the replay with its own sum)."""

from __future__ import annotations

import zlib
from collections.abc import Iterable

STATE_COLORS = ("#5b8def", "#e0823d", "#43a047", "#ab47bc", "#ef5350", "#26a69a", "#8d6e63", "#546e7a")
MAX_NAMED = 256  # names given a colour in one replay (a supervisor has a handful of states)


def state_color(name: str) -> str:
    """The colour of a state (or label) name: the same name, the same colour, on every page."""
    return STATE_COLORS[zlib.crc32(name.encode("utf-8", "replace")) % len(STATE_COLORS)]


def state_colors(names: Iterable[str]) -> dict[str, str]:
    """{name: colour} of the distinct names, the first MAX_NAMED of them."""
    out: dict[str, str] = {}
    for name in names:
        if len(out) >= MAX_NAMED:
            break
        if name and name not in out:
            out[name] = state_color(name)
    return out
