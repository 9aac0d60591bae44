"""What of a submission is compared: the student's code blocks, the handout's own text taken out.

Only the text between ``# START CODE BLOCK`` and ``# END CODE BLOCK`` in the week's course files counts
(read with the course's block reader, simiam.course.blocks); in each block, the lines the handout has in
the same block (the placeholder ``u_x = 0``, an earlier week's block the handout ships filled in) are
blanked before tokenising, so that a student who left them as they were shares nothing with anybody.
The handout is the week's stub as the course ships it (solutions/ in a checkout, through
simiam.course.shipped), or the packaged skeleton (placeholders only) where there are no solutions.

Student files are hostile: they arrive as bytes from grader.batch.submissions (all its limits), are
decoded leniently, never executed nor imported, and at most MAX_CHARS characters of a student's blocks
(MAX_BLOCK_CHARS of one) are compared (the course's largest week has 7 KB of blocks).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

from simiam.course.blocks import BlockError, dedent_body, find_blocks, source_lines
from simiam.course.shipped import shipped_version
from simiam.course.skeleton_stamp import SKELETONS
from simiam.course.weeks import get_week, placeholder_for

MAX_CHARS = 64 * 1024     # a student's compared text; beyond it the blocks are cut, and a note says so
MAX_BLOCK_CHARS = 16 * 1024   # one block's (the course's longest is under 2 KB): one huge block in an early
                              # file must not crowd the others out


@dataclass(frozen=True)
class ComparedBlock:
    """One code block of a student: ``text`` as written (dedented), ``compared`` the same text with the
    handout's lines blanked (same length, so offsets in one are offsets in the other)."""

    file: str
    scope: str
    occurrence: int
    text: str
    compared: str

    @property
    def label(self) -> str:
        """``go_to_goal.py: GoToGoal.execute (block 2)``."""
        more = f" (block {self.occurrence})" if self.occurrence > 1 else ""
        scope = self.scope if len(self.scope) <= 80 else self.scope[:79] + "…"  # names from student code
        return f"{self.file}: {scope}{more}"


@dataclass
class StudentCode:
    """A student's compared blocks, and what the page says about how they were read. ``name`` is the
    one their Identity gives (the platform's or the roster's; "" for a class folder without a roster)."""

    id: str
    blocks: list[ComparedBlock] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    name: str = ""


def handout_text(week: int, name: str) -> str | None:
    """The file ``name`` as the handout of ``week`` ships it (None if the week has no such file)."""
    shipped = shipped_version(week, name)
    if shipped is not None:
        return shipped
    skeleton = SKELETONS / f"week{week}" / name
    return skeleton.read_text(encoding="utf-8") if skeleton.is_file() else None


@lru_cache(maxsize=64)
def handout_lines(week: int, name: str) -> dict[tuple[str, int], frozenset[str]]:
    """Per block (scope, occurrence) of the handout's file, its lines (stripped, code lines only), with
    the declared placeholder's lines too (a stub that is not at hand still has them)."""
    text = handout_text(week, name) or ""
    lines: dict[tuple[str, int], set[str]] = {}
    for block in find_blocks(text, name):
        lines.setdefault(block.key, set()).update(_code_lines(block.body))
        spec = placeholder_for(name, block.scope, block.occurrence, week)
        if spec is not None:
            lines[block.key].update(_code_lines(spec.code))
    return {key: frozenset(found) for key, found in lines.items()}


def handout_blocks(week: int) -> list[ComparedBlock]:
    """The handout's own blocks (their fingerprints are nobody's: the comparer discards them)."""
    out = []
    for name in get_week(week).student_files:
        text = handout_text(week, name)
        for block in find_blocks(text, name) if text else []:
            body = dedent_body(block.body)
            out.append(ComparedBlock(name, block.scope, block.occurrence, body, body))
    return out


def _code_lines(text: str) -> set[str]:
    return {s for ln in source_lines(text, keepends=False) if (s := ln.strip()) and not s.startswith("#")}


def student_code(sid: str, files: dict[str, bytes], week: int) -> StudentCode:
    """The compared blocks of one student's files (``{path: bytes}`` as read_submission gives them)."""
    code = StudentCode(sid)
    budget = MAX_CHARS
    for name in get_week(week).student_files:
        data = files.get(name)
        if data is None:
            continue
        text = data.decode("utf-8", errors="replace").removeprefix("\ufeff")
        try:
            blocks = find_blocks(text, name)
        except BlockError as exc:
            code.notes.append(f"{name}: {exc.message} (line {exc.line}); its blocks could not be told apart, "
                              "so this file was not compared")
            continue
        own = handout_lines(week, name)
        for block in blocks:
            if budget <= 0:
                code.notes.append(f"{name}: blocks past the first {MAX_CHARS} characters were not compared")
                return code
            body = dedent_body(block.body[:4 * MAX_BLOCK_CHARS])
            cut = body[:min(budget, MAX_BLOCK_CHARS)]
            budget -= len(cut)
            compared = ComparedBlock(name, block.scope, block.occurrence, cut,
                                     _blank(cut, own.get(block.key, frozenset())))
            if len(cut) < len(body):
                code.notes.append(f"{compared.label} was cut to {len(cut)} characters")
            code.blocks.append(compared)
    if not code.blocks and not code.notes:
        code.notes.append("no code block found in the week's files")
    return code


def _blank(body: str, handout: frozenset[str]) -> str:
    """``body`` with its handout lines turned into spaces (so offsets do not move), comments kept."""
    if not handout:
        return body
    out = []
    for line in source_lines(body):
        content = line.rstrip("\r\n")
        out.append(" " * len(content) + line[len(content):] if content.strip() in handout else line)
    return "".join(out)


def handout_source(week: int) -> str:
    """Where the handout's text comes from, as the page says it."""
    if shipped_version(week, get_week(week).student_files[0]) is not None:
        return f"the week-{week} handout as the course ships it"
    return "the packaged skeletons (placeholders only: run from the course checkout to also take out " \
           "the earlier weeks' blocks the handout ships filled in)"
