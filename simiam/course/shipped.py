"""Files a student may leave out: the ones with no code block new this week, which the course ships complete.

`grade` and `simiam run` both fill such a missing file in, with the same words: from the instructor's
solutions/ where a checkout is at hand (the file as the course ships it, earlier weeks' blocks filled in),
else from the packaged skeleton, whose blocks are placeholders because the package holds no answers.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from simiam.course.weeks import get_week

ROOT = Path(__file__).resolve().parents[2]


def files_to_write(week: int) -> set[str]:
    """The files with a code block that is new in `week` (the others ship complete and may be missing)."""
    return set(get_week(week).files_to_write)


def shipped_version(week: int, name: str, root: Path = ROOT) -> str | None:
    """`name` as the course ships it in `week` (earlier weeks' blocks filled in), where the instructor's
    solutions/ is at hand (a checkout, official grading); None in a student's installation."""
    solution = root / "solutions" / f"week{week}" / name
    if not solution.is_file():
        return None
    return _stubbed(week, solution.read_text(encoding="utf-8"), name)


@lru_cache(maxsize=128)
def _stubbed(week: int, solution_text: str, name: str) -> str:
    """The shipped text of a solution file, kept per text (a batch ships the same files to every student)."""
    from simiam.course.stubs import stub_text

    return stub_text(week, solution_text, name)[0]


def missing_note(week: int, name: str, shipped: bool) -> str:
    """What the feedback says about a missing file the student writes nothing in this week."""
    if shipped:
        return (f"{name} is missing from your submission: you write nothing in it this week, so the version "
                "the course ships was used")
    return (f"{name} is missing from your submission: you write nothing in it this week, but the course "
            "ships it with earlier weeks' code filled in, which this installation does not hold (it holds "
            f"no answers), so its blocks were left empty: copy {name} from your week{week} handout")
