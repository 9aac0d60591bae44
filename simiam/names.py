"""A misspelt name, named: the names that are known, the closest first, and the one it most likely meant.

Used where a name nobody reads would otherwise be accepted silently: a supervisor setting or gain
(simiam.course.week, LocalBrain), an attribute in a world file (simiam.world.settings_xml), and a state
or event name a supervisor is given (simiam.control.supervisor).
"""

from __future__ import annotations

from collections.abc import Iterable


def closest_first(name: str, known: Iterable[str]) -> list[str]:
    """The `known` names, the most like `name` first (difflib's similarity ratio, the one its
    get_close_matches ranks suggestions by; equally close names keep their order)."""
    import difflib  # only when a name is wrong: the sandbox worker imports this module on every start

    return sorted(known, key=lambda k: -difflib.SequenceMatcher(None, k, name).ratio())


def likely_meant(name: str, known: Iterable[str], cutoff: float = 0.6) -> str | None:
    """The known name `name` most likely meant: the same name in other capitals, else difflib's best
    match (similarity `cutoff` or more); None when nothing is close."""
    import difflib

    known = list(known)
    same = [k for k in known if k.lower() == name.lower()]
    close = same or difflib.get_close_matches(name, known, n=1, cutoff=cutoff)
    return close[0] if close else None


def shown(name: object) -> str:
    """`name` as repr, capped at 80 characters: a student's wrong name can be any object, of any size."""
    text = repr(name)
    return text if len(text) <= 80 else text[:77] + "..."


def unknown_name(kind: str, name: object, known: Iterable[str], of: str = "") -> str:
    """"unknown setting 'd_fww' (did you mean 'd_fw'?); the settings are, closest first: d_fw, ...":
    the name (shown as repr, capped), the likely meant one, and every known name, closest first (`of`:
    whose names they are, e.g. "<pose>")."""
    if not isinstance(name, str):
        return f"a {kind}'s name is a string, not {type(name).__name__} {shown(name)}"
    ranked = closest_first(name, known)
    meant = likely_meant(name, ranked)
    guess = f" (did you mean {meant!r}?)" if meant else ""
    whose = f" of {of}" if of else ""
    listed = ", ".join(ranked) or "none"
    return f"unknown {kind} {shown(name)}{guess}; the {kind}s{whose} are, closest first: {listed}"
