"""The instructor's hidden set: parameters of the hidden scenario variants, kept as data.

`grade --hidden` runs the hidden checks; those that need data read it from `$SIMIAM_HIDDEN/weekN.json`
when that variable names a folder, else from the course checkout's instructor_tools/hidden/. The student
package (a wheel) holds no hidden set: it grades every visible check and says the hidden ones run at
official grading.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any


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
