"""A feedback zip for a course platform: each student's report under the entry name the platform places."""

from __future__ import annotations

import zipfile
from collections.abc import Callable
from pathlib import Path

from grader.batch.posted import Posted
from grader.batch.store import replacing


def write_feedback_zip(path: Path, rows: list[Posted], pages: dict[str, Path],
                       entry: Callable[[Posted], str], no_entry: str) -> tuple[int, dict[str, str]]:
    """Write the zip at ``path``: the report of every row that has one, named ``entry(row)`` (fixed dates,
    so the same reports give the same bytes). Returns how many went in and {id: why} for those that did
    not (``no_entry`` where ``entry`` gives no name); a student without a report is no entry at all."""
    placed, unplaced = 0, {}
    with replacing(path) as stream, zipfile.ZipFile(stream, "w", zipfile.ZIP_DEFLATED) as archive:
        for row in rows:
            sid = row.identity.id
            page = pages.get(sid)
            if page is None:
                continue                # no report: a blank grade, said in the export's `blank`
            name = entry(row)
            if not name:
                unplaced[sid] = no_entry
                continue
            try:
                data = page.read_bytes()
            except OSError as exc:
                unplaced[sid] = f"report not readable: {exc.strerror}"
                continue
            archive.writestr(zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0)), data,
                             compress_type=zipfile.ZIP_DEFLATED)
            placed += 1
    return placed, unplaced
