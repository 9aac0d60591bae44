"""The docs say what holds now, never who worked when (issue 33): no work-period numbers ("session 7"),
no "this session" / "last session", no names of temporary branches or their worktree paths ("helper
sim26", "branch s24", "/work/wt-pages"). A figure is dated by its commit and its date, a change by its
commit or version. The sandbox's own sessions (StudentSession, "the session refuses to start") are code
terms and pass.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
WRONG = ROOT / "tests" / "data" / "docs_wrong" / "diary.md"
DIARY = re.compile(
    r"\bsessions? \d+\b|\b(?:this|last|previous|next|earlier|later) session\b|\bhelpers? [a-z]+\d+\b"
    r"|\bhelper `|\bwork periods?\b|\bbranch `?s\d+\b|/work/wt-|\bwt-[a-z]+\b",
    re.IGNORECASE)


def diary_lines(path: Path) -> list[str]:
    """'file:line: text' for every line of `path` that dates the work by who did it or when."""
    lines = path.read_text(encoding="utf-8").splitlines()
    return [f"{path.relative_to(ROOT)}:{n}: {text.strip()}" for n, text in enumerate(lines, 1)
            if DIARY.search(text)]


def test_docs_state_what_holds_not_who_worked_when() -> None:
    found = [line for path in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
             for line in diary_lines(path)]
    assert found == [], "\n".join(found)


def test_a_diary_is_caught() -> None:
    """The wrong version: seven diary lines, each caught; the sandbox's own sessions pass."""
    found = diary_lines(WRONG)
    assert [line.split(": ", 1)[1] for line in found] == [
        "Issue 24 after session 7: where it stands.",
        "The step is 1.6x faster than in the last session.",
        "In this session the probes went into batches.",
        "Measured by helper sim26 on the shared machine.",
        "The figures of this work period replace the earlier ones.",
        "Batched steps (branch s24, kept for the record) were slower.",
        "Built in /work/wt-pages and merged later.",
    ], "\n".join(found)
