"""Earlier weeks' parts in a scenario: the course's versions, so that a week-4 mistake does not sink week 5.

From week 5 on a scenario drives the robot with every block the student ever wrote (odometry, IR distances,
GoToGoal, AvoidObstacles, ...). A check module that opts in (`scenario_session(ctx)`) runs its scenarios on a
second copy of the submission: each file as the course ships it this week (earlier weeks' blocks filled in
with the course's answers), with only the blocks NEW this week taken from the student's spliced file. The
earlier blocks are graded in their own weeks.

Where the course's versions come from: the instructor's solutions/ (a checkout, `grade --solutions`,
batch grading), else the week's handout named by $SIMIAM_HANDOUT (a Gradescope bundle's grading sets it to
the handout the bundle carries). A student's own installation holds neither (it holds no answers): there the
scenarios run the student's own earlier blocks, and `note` says so.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from simiam.course.blocks import BlockError, find_blocks, replace_bodies
from simiam.course.shipped import ROOT, shipped_version
from simiam.course.weeks import get_week

OWN_CODE_NOTE = ("the runs used your own code for earlier weeks' parts (this installation does not hold the "
                 "course's versions); official grading uses the course's")


def _shipped(week: int, name: str) -> str | None:
    """`name` as the course ships it in `week`: from solutions/ in a checkout, else from $SIMIAM_HANDOUT."""
    text = shipped_version(week, name, ROOT)
    if text is not None:
        return text
    handout = os.environ.get("SIMIAM_HANDOUT")
    path = Path(handout) / name if handout else None
    if path is not None and path.is_file():
        return path.read_text(encoding="utf-8")
    return None


def reference_folder(week: int, spliced: Path, into: Path) -> Path | None:
    """A copy of the spliced submission in `into` whose earlier weeks' blocks are the course's versions
    (this week's blocks stay the student's); None when the course's versions are not at hand."""
    config = get_week(week)
    new = {b.key for b in config.blocks}  # (file, scope, occurrence) of this week's blocks
    into.mkdir(parents=True, exist_ok=True)
    for name in config.student_files:
        shipped = _shipped(week, name)
        if shipped is None:
            return None
        student_file = spliced / name
        if not student_file.is_file():
            continue  # did not splice: the load error is the student's, reported by the main session
        student = student_file.read_text(encoding="utf-8")
        try:
            theirs = {b.key: b.body for b in find_blocks(student, name)}
            ours = find_blocks(shipped, name)
        except BlockError:
            return None
        bodies = {b.ordinal: theirs[b.key] for b in ours if (name, *b.key) in new and b.key in theirs}
        (into / name).write_text(replace_bodies(shipped, ours, bodies), encoding="utf-8")
    return into


SESSION_KEY = "earlier:session"  # in ctx.memo: kept when a stalled check is run again (grader.under_load)


def scenario_session(ctx: Any) -> tuple[Any, str]:
    """The session a week's scenarios run on, and a note for the check's message ("" when all is as it
    should be). Made once per grading (ctx.memo) through the engine's `ctx.open_session`, on the grading's
    one time budget."""
    key = SESSION_KEY
    if key not in ctx.memo:
        folder = None
        if ctx.spliced is not None and ctx.open_session is not None:
            folder = reference_folder(ctx.week, Path(ctx.spliced), Path(ctx.spliced).parent / "earlier")
        if folder is None:
            ctx.memo[key] = (ctx.session, OWN_CODE_NOTE)
        elif same_files(folder, Path(ctx.spliced)):  # the earlier blocks are the course's already (as the
            ctx.memo[key] = (ctx.session, "")         # handout ships them): the worker at hand runs that code
        else:
            ctx.memo[key] = (ctx.open_session(folder), "")
    return ctx.memo[key]


def same_files(a: Path, b: Path) -> bool:
    """Whether folders `a` and `b` hold the same files (names and bytes; no subfolders in either): then a
    worker loading one runs the same code as one loading the other, and a second worker (a sandbox start,
    about 0.1 CPU-s) is not needed."""
    try:
        names_a, names_b = sorted(p.name for p in a.iterdir()), sorted(p.name for p in b.iterdir())
        if names_a != names_b:
            return False
        return all((a / n).is_file() and not (a / n).is_symlink() and (b / n).is_file()
                   and not (b / n).is_symlink() and (a / n).read_bytes() == (b / n).read_bytes()
                   for n in names_a)
    except OSError:
        return False
