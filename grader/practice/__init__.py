"""The practice set: hidden-like variants that ship with the student's package, never graded.

Official grading's hidden checks run variants from the instructor's hidden set (grader.hidden), which
never leaves the course checkout. `grade weekN --practice` runs the same checks on the variants here
instead: drawn the same way (same generator, same margins vetted on the reference solution) but never a
hidden variant, so a student can try the robustness the hidden checks test before submitting. A practice
result is shown apart ("practice, not graded") and never counts toward the score.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

PRACTICE_DIR = Path(__file__).resolve().parent

# The weeks with a practice set (grader/practice/weekN.json): those whose hidden checks run scenario
# variants (week 2's hidden check draws other angles per seed; a practice set there is not needed yet).
WEEKS_WITH_PRACTICE = (3, 4, 5, 6, 7)

PRACTICE_NOTE = ("Practice, not graded: these checks ran the practice variants shipped with the course "
                 "package, never the hidden ones. Official grading runs the same checks on other variants, "
                 "drawn the same way from the instructor's hidden set; passing here does not guarantee "
                 "them, and no practice result counts toward your score.")


def load_practice(week: int) -> dict[str, Any] | None:
    """The practice set of `week` ({"about", "variants"}), or None when the week has none."""
    path = PRACTICE_DIR / f"week{int(week)}.json"
    if not path.is_file():
        return None
    return json.loads(path.read_text(encoding="utf-8"))


def missing_practice_set(weeks: list[int]) -> None:
    """Raise ValueError when `--practice` asks for a week without a practice set."""
    missing = [w for w in weeks if load_practice(w) is None]
    if missing:
        which = ", ".join(f"week {w}" for w in missing)
        have = ", ".join(str(w) for w in WEEKS_WITH_PRACTICE)
        raise ValueError(f"--practice: {which} has no practice set (weeks {have} have one: their hidden "
                         "checks run scenario variants)")


def variants_to_run(ctx: Any, week: int, pick: Callable[[dict[str, Any]], list[dict[str, Any]]],
                    keep: Callable[[dict[str, Any]], bool] = lambda v: True) -> list[dict[str, Any]] | None:
    """The variants a hidden check of `week` runs: with `ctx.practice`, every practice variant `keep`
    accepts; otherwise `pick(data)` of the instructor's hidden set (the seed's draw). None when the set
    needed is not here (a student's package has no hidden set)."""
    if getattr(ctx, "practice", False):
        data = load_practice(week)
        return None if data is None else [v for v in data["variants"] if keep(v)]
    from grader.hidden import load_hidden

    hidden = load_hidden(week)
    return None if not hidden else pick(hidden)


def not_here(ctx: Any) -> str:
    """What a hidden check says when the variants it needs are not here."""
    if getattr(ctx, "practice", False):
        return "this installation has no practice set for this week"
    return "the instructor's hidden set is not here (it runs at official grading)"
