"""A code block of the course, as data: which week it is new in, and what a stub holds instead.

Each week declares the blocks new that week (`Week.blocks`, in simiam/course/weeks/weekN.py); each block of
`solutions/weekN` is looked up among all weeks' blocks by (file, enclosing function, position in that
function) with `simiam.course.weeks.placeholder_for` (the weeks import this module, not the other way).
In the week it is introduced its body is replaced by `hint` (comment lines) and `code` (a placeholder that
runs: the robot stays still or drives straight); in later weeks the solution's body ships filled in.

`revised_in` lists the weeks whose stubs ship a *changed* filled version (the course changed the robot or
the provided code around the block): `simiam migrate` keeps the shipped version there instead of carrying
the student's older one. `tunable` blocks (gains) may ship other values in later weeks and are carried
all the same. A test compares the declared blocks with the solutions, so it cannot silently drift.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Placeholder:
    """What the stub of `week` puts in the block `scope` (occurrence `occurrence`) of `file`."""

    file: str
    scope: str
    hint: str
    code: str
    week: int = 0  # filled in by the Week that declares the block
    occurrence: int = 1
    revised_in: tuple[int, ...] = ()
    revised_why: str = ""
    tunable: bool = False  # numbers to tune: later weeks may ship other values, yet migrate carries yours

    @property
    def key(self) -> tuple[str, str, int]:
        return (self.file, self.scope, self.occurrence)

    def body(self, indent: str) -> str:
        """The placeholder as block body text at `indent`: the hint as comments, then the code."""
        lines = [f"# {ln}".rstrip() for ln in self.hint.strip().splitlines()]
        lines += self.code.strip().splitlines()
        return "".join(f"{indent}{ln}\n" if ln.strip() else "\n" for ln in lines)

