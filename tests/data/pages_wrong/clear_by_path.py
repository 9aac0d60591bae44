"""A wrong way to remove a student's old replay pages before a regrade (tests/batch/test_batch_pages.py):
by path, so a link planted at replays/<stem> is followed and the files it points to are deleted."""

from __future__ import annotations

from pathlib import Path


def clear(out: Path, stem: str) -> None:
    for page in (out / "replays" / stem).glob("*.html"):
        page.unlink()
