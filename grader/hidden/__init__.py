"""The instructor's hidden set: parameters of the hidden scenario variants, kept as data.

`grade --hidden` (and a batch, unless --visible-only) runs the hidden checks; those that need data read
it from `$SIMIAM_HIDDEN/weekN.json` when that variable names a folder, else from the course checkout's
instructor_tools/hidden/. Which hidden set a grading ran is recorded by grader/hidden/identity.py. The
student package (a wheel) holds no hidden set: it grades every visible check and says the hidden ones run
at official grading.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

# The weeks whose hidden checks read the hidden set (the others draw theirs from the seed alone); the
# checkout holds instructor_tools/hidden/weekN.json for exactly these (tests/grader/test_hidden.py).
WEEKS_WITH_DATA = (4, 5, 6, 7)


def hidden_dir() -> Path:
    """Where the hidden set lives: $SIMIAM_HIDDEN, else the checkout's instructor_tools/hidden (which
    does not exist in a student package)."""
    from simiam.course.folders import INSTRUCTOR_TOOLS

    env = os.environ.get("SIMIAM_HIDDEN")
    return Path(env) if env else INSTRUCTOR_TOOLS / "hidden"


def load_hidden(week: int) -> dict[str, Any] | None:
    """The hidden data of `week`, or None when the hidden set is not present."""
    path = hidden_dir() / f"week{int(week)}.json"
    if not path.is_file():
        return None
    return json.loads(path.read_text(encoding="utf-8"))


def missing_hidden_set(weeks: list[int]) -> None:
    """Raise ValueError, in words a student understands, when `--hidden` asks for the hidden checks of a
    week whose hidden set this installation does not hold (a student's wheel): each such check would only
    show as an error."""
    missing = [w for w in weeks if w in WEEKS_WITH_DATA and load_hidden(w) is None]
    if not missing:
        return
    which = ", ".join(f"week {w}" for w in missing)
    raise ValueError(f"--hidden runs the hidden checks of {which}, which read the instructor's hidden set: "
                     "it is in the course checkout (instructor_tools/hidden/) or in the folder "
                     "$SIMIAM_HIDDEN names, and this installation has neither. The hidden checks run at "
                     "official grading; without --hidden, grade runs every visible check.")
