"""A student's pages in a batch: the report, its replay pages, and the replay's script and styles shared by
the class.

A report written by ``grade weekN`` carries every replay inside it (one file a student can open or mail on
its own, ~0.3-1.4 MB). In a batch the same replays would repeat the replay's script and styles (~40 KB)
once per run and student, so a batch writes them once::

    --out/assets/replay.js, replay.css     the replay's script and styles (shared_assets)
    --out/<stem>.html                      the student's report (compact plots), linking each run's replay
    --out/replays/<stem>/<run>.html        one replay page per run, loading ../../assets/

The replay pages keep the rows the self-contained report embeds (grader.report.html.render_report_pages):
the same run plays. Every file goes through grader.batch.store's writers (never through a link).
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import stat
from pathlib import Path
from urllib.parse import quote

from grader.batch.store import write_atomic
from grader.result_size import bound_html
from simiam import safe_write

ASSETS = "assets"
REPLAYS = "replays"
ASSETS_FROM_REPLAY = f"../../{ASSETS}"    # from replays/<stem>/<run>.html
# A replay page's file name as the report names it (grader.report.html._slug), never hidden or a parent.
_PAGE_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,150}\.html")
MAX_REPLAY_PAGES = 200


def replay_folder(stem: str) -> str:
    """The URL of a student's replay folder, relative to their report (and to ``--out``)."""
    return f"{REPLAYS}/{quote(stem)}"


def write_assets(out: Path) -> None:
    """Write ``out/assets/``: the files every batch replay page loads (written on every run, so they are
    those of the grader that wrote the pages: a changed viewer changes the grader fingerprint, which
    regrades every student)."""
    from simiam.viewer.replay import shared_assets

    for name, text in shared_assets().items():
        write_atomic(out / ASSETS / name, text)


def replay_pages(value: object) -> dict[str, str]:
    """The replay pages of a grading outcome (``{"replays": {name: html}}``), only those with a plain
    file name and a bounded size; anything else is left out (the report then has a dead link, never a
    file outside the student's folder)."""
    pages = value.get("replays") if isinstance(value, dict) else None
    if not isinstance(pages, dict):
        return {}
    kept = {}
    for name, page in list(pages.items())[:MAX_REPLAY_PAGES]:
        if isinstance(name, str) and _PAGE_NAME.fullmatch(name) and isinstance(page, str):
            bounded = bound_html(page)
            if bounded is not None:
                kept[name] = bounded
    return kept


def write_student_pages(out: Path, stem: str, html: str, replays: dict[str, str]) -> None:
    """Write a student's replay pages, then their report (which links them): the pages of an earlier
    grading of this student are removed first, so the folder holds this grading's runs only."""
    _clear(out, stem)
    for name, page in replays.items():
        write_atomic(out / REPLAYS / stem / name, page)
    write_atomic(out / f"{stem}.html", html)


def _clear(out: Path, stem: str) -> None:
    """Remove the ``.html`` files of ``out/replays/<stem>/``, opening each folder below ``out`` without
    following a link (a link there is refused) and unlinking by name (which never follows one)."""
    fds: list[int] = []
    try:
        try:
            fd = os.open(out, os.O_RDONLY | os.O_DIRECTORY)
        except FileNotFoundError:
            return
        fds.append(fd)
        path = out
        for part in (REPLAYS, stem):
            path = path / part
            try:
                fd = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=fd)
            except FileNotFoundError:
                return
            except OSError as exc:   # a link: ELOOP, or ENOTDIR with O_DIRECTORY
                if exc.errno == errno.ELOOP or stat.S_ISLNK(os.lstat(part, dir_fd=fd).st_mode):
                    raise safe_write.LinkRefused(path) from None
                raise
            fds.append(fd)
        for name in os.listdir(fd):
            if name.endswith(".html"):
                with contextlib.suppress(FileNotFoundError, IsADirectoryError, PermissionError):
                    os.unlink(name, dir_fd=fd)
    finally:
        for opened in fds:
            os.close(opened)
