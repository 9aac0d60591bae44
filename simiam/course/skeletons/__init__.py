"""The pristine skeletons: every student file of every week with every block reduced to its placeholder.

They ship inside the package (package data under `weekN/`), generated from solutions/ by
`python -m simiam.course.stubs` and checked for drift by tests/course/test_stubs.py. The grader splices a
submission's blocks only into these, never into a folder a student can edit (assignments/weekN is what a
student edits, even in a checkout). They hold no solution code of any week: outside the blocks they are
the week's stubs line for line; inside, the placeholders (the stubs students receive ship earlier weeks'
blocks filled, the course's answers to those weeks, which a package every student installs must not hold).
A file missing from a submission is therefore graded as the placeholder skeleton.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path


class SkeletonsMissing(RuntimeError):
    """The package was installed without its skeleton data (a broken build): nothing can be spliced."""


def skeleton_files(week: int) -> dict[str, str]:
    """{file name: text} of week `week`'s skeleton files (the .py files a student receives)."""
    folder = resources.files(__name__).joinpath(f"week{int(week)}")
    files = {}
    if folder.is_dir():
        files = {p.name: p.read_text(encoding="utf-8") for p in folder.iterdir() if p.name.endswith(".py")}
    if not files:
        raise SkeletonsMissing(
            f"the skeleton files of week {week} are missing from this installation of simiam "
            f"({folder}); reinstall the package (a wheel built from the course checkout ships them)"
        )
    return dict(sorted(files.items()))


def write_skeleton(week: int, folder: Path) -> Path:
    """Write week `week`'s skeleton files into `folder` (created) and return it."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in skeleton_files(week).items():
        (folder / name).write_text(text, encoding="utf-8")
    return folder
