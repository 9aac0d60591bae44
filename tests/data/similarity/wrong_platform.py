"""Wrong versions of similarity on a platform's download, kept so that tests/batch/test_batch_similarity.py
proves it catches each. Each entry is (module path, attribute, replacement): what the test patches in."""

from __future__ import annotations

from pathlib import Path

from markupsafe import Markup

from grader.batch import summary
from grader.batch.intake import ClassList
from grader.batch.store import write_atomic
from grader.batch.submissions import Submission, discover, read_submission
from grader.similarity.page import shown_id
from grader.similarity.students import read_source


def folder_only(source: Path, options: object, out: Path | None = None) -> ClassList:
    """The class read as one folder or zip per student id, whatever SOURCE is (the reader before the
    batch's intake): a Canvas zip is no folder."""
    return ClassList("folder", source, discover(source))


def ids_only(sid: str, name: str = "") -> str:
    """Pairs named by the platform's id alone."""
    return shown_id(sid)


def names_as_markup(sid: str, name: str = "") -> str:
    """The name as the roster wrote it: not cut, and trusted as HTML."""
    return Markup(f"{sid} ({name})")


def held_compared(student: object, limits: object = None, week: int | None = None) -> Submission:
    """A held student compared as if nothing were wrong (with no files: an empty submission)."""
    submission = read_submission(student, week=week)  # type: ignore[arg-type]
    submission.held = None
    return submission


def roster_ignored(source: Path, out: Path | None = None, roster: Path | None = None) -> ClassList:
    """``--roster`` accepted and not read: only the platform's names."""
    return read_source(source, out)


def summary_without_link(out: Path, results: dict, stems: dict, meta: dict) -> None:
    """The summary as it was: no link to similarity.html."""
    write_atomic(out / "summary.html", summary.summary_html(results, stems, meta))


WRONG = {
    "SOURCE read as a class folder": [("grader.similarity.students", "read_class", folder_only)],
    "pairs named by id only": [("grader.similarity.page", "shown_student", ids_only)],
    "names neither cut nor escaped": [("grader.similarity.page", "shown_student", names_as_markup)],
    "held students compared": [("grader.similarity.students", "read_submission", held_compared)],
    "--roster not read": [("grader.similarity.command", "read_source", roster_ignored)],
}
WRONG_BATCH = {"summary without the link": [("grader.batch.runner", "write_summary", summary_without_link)]}
