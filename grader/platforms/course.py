"""Where the instructor's course lives: the checkout holding solutions/ and assignments/.

Packaging and self-checking read the reference solutions, so they run from the course checkout (or name it
with --course). A student install has no solutions/ and is refused with a clear message.
"""

from __future__ import annotations

from pathlib import Path

from grader.grading import ROOT


class CourseNotFound(ValueError):
    """No course checkout (a folder with solutions/week1..) where the command looked."""


def course_root(explicit: Path | str | None = None) -> Path:
    """The course checkout: `explicit`, else the current folder if it holds solutions/, else the checkout
    this package was installed from (an editable install)."""
    candidates = [Path(explicit)] if explicit is not None else [Path.cwd(), ROOT]
    for folder in candidates:
        if (folder / "solutions" / "week1").is_dir():
            return folder.resolve()
    where = " or ".join(str(c) for c in candidates)
    raise CourseNotFound(
        f"no course checkout at {where} (it needs solutions/week1 ...): run this from the course's "
        "repository, or name it with --course DIR"
    )
