"""Wrong versions of the similarity comparer, kept so that tests/similarity proves it catches each.

Each entry is (module path, attribute, replacement): what the test patches in for that wrong version."""

from __future__ import annotations

from simiam.course.blocks import dedent_body, find_blocks
from simiam.course.weeks import get_week

from grader.similarity.submitted import ComparedBlock, StudentCode


def whole_files(sid: str, files: dict[str, bytes], week: int) -> StudentCode:
    """Compares whole files, the handout's text included (every pair shares the stub)."""
    code = StudentCode(sid)
    for name in get_week(week).student_files:
        if name in files:
            text = files[name].decode("utf-8", errors="replace")
            code.blocks.append(ComparedBlock(name, "<module>", 1, text, text))
    return code


def blocks_unblanked(sid: str, files: dict[str, bytes], week: int) -> StudentCode:
    """Compares the code blocks, but keeps the handout's own lines in them (placeholders, the earlier
    weeks' blocks the handout ships filled in)."""
    code = StudentCode(sid)
    for name in get_week(week).student_files:
        if name in files:
            for b in find_blocks(files[name].decode("utf-8", errors="replace"), name):
                body = dedent_body(b.body)
                code.blocks.append(ComparedBlock(name, b.scope, b.occurrence, body, body))
    return code


def names_kept(kind: int, text: str) -> str:
    """Tokens as written: a renamed variable is a different token."""
    return text


def no_handout(week: int) -> list:
    """Nothing of the handout discarded."""
    return []


WRONG = {
    "whole files, handout text included": [("grader.similarity.students", "student_code", whole_files),
                                          ("grader.similarity.command", "handout_blocks", no_handout)],
    "blocks with the handout's lines kept": [("grader.similarity.students", "student_code", blocks_unblanked),
                                             ("grader.similarity.command", "handout_blocks", no_handout)],
    "identifiers not normalised": [("grader.similarity.tokens", "normalised", names_kept)],
}
