"""The weeks of the course: one file per week, `weekN.py` holding `WEEK = Week(...)`, found by name.

`get_week(3)` (or "3", "week3") returns week 3's declaration; `all_weeks()` every week in order;
`week_numbers()` their numbers; `spec_for_week(3)` the QuickBot week 3 drives; `placeholder_for` a block
declared by some week. Nothing lists the weeks by hand: a `weekN.py` in this package is a week of
the course (see docs/design.md, "Adding a week"), so adding a week is adding a file.
"""

from __future__ import annotations

import functools
import importlib
import pkgutil
import re

from simiam.course.placeholders import Placeholder
from simiam.course.week import Week
from simiam.robot.quickbot import RobotSpec

_WEEK_MODULE = re.compile(r"week([1-9][0-9]*)")
# What hidden checks vary, in words, for a week that does not say (or a result of a week not declared here)
HIDDEN_VARIANTS_UNSAID = "other goals, other worlds"


@functools.cache
def _registry() -> dict[int, Week]:
    """Import every weekN module of this package; their WEEKs by number (checked against the file name)."""
    found: dict[int, Week] = {}
    for info in pkgutil.iter_modules(__path__):
        match = _WEEK_MODULE.fullmatch(info.name)
        if match is None:
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        week = getattr(module, "WEEK", None)
        if not isinstance(week, Week):
            raise TypeError(f"{module.__file__}: a week file must define WEEK = Week(...)")
        if week.number != int(match.group(1)):
            raise ValueError(f"{module.__file__}: declares week {week.number}, its file name says "
                             f"week {match.group(1)}")
        found[week.number] = week
    return dict(sorted(found.items()))


def refresh() -> None:
    """Look for week files again (after one was added to this package's path, e.g. in a test)."""
    _registry.cache_clear()
    importlib.invalidate_caches()


def week_numbers() -> tuple[int, ...]:
    """The numbers of the course's weeks, in order: (1, 2, 3, 4, ...)."""
    return tuple(_registry())


def all_weeks() -> tuple[Week, ...]:
    """Every week's declaration, in order."""
    return tuple(_registry().values())


def get_week(week: int | str) -> Week:
    """The declaration of a week, given as 3, "3" or "week3"; a ValueError names the weeks there are."""
    text = str(week).strip().lower().removeprefix("week").strip()
    weeks = _registry()
    if isinstance(week, bool) or not text.isdigit() or int(text) not in weeks:
        listed = ", ".join(f"week{n}" for n in weeks)
        raise ValueError(f"no such week: {week!r} (the course has {listed})")
    return weeks[int(text)]


def hidden_variants(week: object) -> str:
    """In a few words, what the hidden checks of `week` (3, "3", "week3": e.g. a result's "week") vary:
    the week's own `hidden_variants`, or the generic words for a week that is not declared or says
    nothing. For the lines that count hidden checks (grade's terminal output, the report, the platforms)."""
    try:
        return get_week(week).hidden_variants or HIDDEN_VARIANTS_UNSAID  # type: ignore[arg-type]
    except ValueError:
        return HIDDEN_VARIANTS_UNSAID


def previous_week(week: int) -> int:
    """The declared week before `week` (the one `simiam migrate` carries blocks from); ValueError for the
    first week or an undeclared one."""
    numbers = week_numbers()
    number = get_week(week).number
    if number == numbers[0]:
        raise ValueError(f"week {number} is the first week of the course")
    return numbers[numbers.index(number) - 1]


def spec_for_week(week: int | str) -> RobotSpec:
    """The QuickBot of course week `week`, as the week declares it (simiam/course/weeks/weekN.py): the
    course asks the robot model for the robot it needs, the robot model knows no weeks."""
    return get_week(week).spec


def all_blocks() -> tuple[Placeholder, ...]:
    """The code blocks of every week (each new in its week), in week order."""
    return tuple(block for week in all_weeks() for block in week.blocks)


def placeholder_for(file: str, scope: str, occurrence: int = 1,
                    week: int | None = None) -> Placeholder | None:
    """The declared block of (file, scope, occurrence), or None.

    A later week may declare a new block where an earlier week had one (week 7's automaton fills the
    place of week 5's switching in `QBSupervisor.execute`): in `week`, the block of the latest week up to
    it is the one meant. Without a week: the first week's."""
    found = None
    for p in all_blocks():  # in week order
        if p.key == (file, scope, occurrence):
            if week is None:
                return p
            if p.week <= week:
                found = p
    return found


__all__ = ["HIDDEN_VARIANTS_UNSAID", "Week", "all_blocks", "all_weeks", "get_week", "hidden_variants",
           "placeholder_for", "previous_week", "refresh", "spec_for_week", "week_numbers"]
