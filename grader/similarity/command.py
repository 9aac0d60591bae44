"""``grade similarity weekN SOURCE``: which students' code blocks look alike, for the instructor to read.

    grade similarity week3 submissions/ --out graded-week3/     # next to the batch's summary.html
    grade similarity week3 submissions/ --threshold 0.5 --common 20

SOURCE is the class folder of ``grade weekN --batch`` (one sub-folder or ``.zip`` per student id), read
with the batch's own readers and limits. Writes ``similarity.html`` and ``similarity.json`` to ``--out``
(default ``reports/similarity-weekN``) and prints the best pairs. Exit status 0 when the report is
written (whatever it found), 2 when it could not run.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TextIO

from grader.batch.names import shown
from grader.batch.store import write_atomic, write_json
from grader.batch.submissions import discover, read_submission
from grader.similarity.compare import MAX_COMMON, common_limit, compare
from grader.similarity.fingerprints import WINDOW, K
from grader.similarity.page import print_top, report_json, similarity_html
from grader.similarity.submitted import StudentCode, handout_blocks, handout_source, student_code
from grader.untrusted import printable
from simiam.course.weeks import get_week

THRESHOLD = 0.6   # measured: copies 0.70-1.00, independent week-3 solutions at most 0.49 (docs/batch.md)


class SimilarityError(Exception):
    """The comparison cannot run (no such folder, no students); the message says why."""


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="grade similarity",
        description="Compare the students' code blocks (the handout's own text removed) and rank the "
                    "pairs that look alike. It flags pairs; a person decides.")
    p.add_argument("week", help="weekN: the assignment the submissions are for")
    p.add_argument("source", help="the class folder: one sub-folder or .zip per student id")
    p.add_argument("--out", default=None, help="folder for similarity.html and similarity.json "
                   "(default reports/similarity-weekN; the batch's --out folder is a good place)")
    p.add_argument("--threshold", type=float, default=THRESHOLD,
                   help=f"lowest score shown, 0..1 (default {THRESHOLD})")
    p.add_argument("--common", type=int, default=None,
                   help=f"a passage found in more submissions than this counts for nobody (default "
                        f"{MAX_COMMON}, as MOSS, or a tenth of the class, whichever is more)")
    p.add_argument("--top", type=int, default=10, help="pairs printed (default 10)")
    return p


def read_class(source: Path, week: int, out: Path | None = None) -> tuple[list[StudentCode], dict[str, str]]:
    """Every student's compared code, and {id: why} for those whose submission could not be read."""
    if not source.is_dir():
        raise SimilarityError(f"{source} is not a folder of submissions")
    out_resolved = out.resolve() if out is not None else None
    codes: list[StudentCode] = []
    refused: dict[str, str] = {}
    for student in discover(source):
        where = student.path.resolve()
        if out_resolved is not None and (where == out_resolved or where in out_resolved.parents):
            continue          # the output folder inside the class folder is no student
        submission = read_submission(student, week=week)
        if submission.refused:
            refused[student.id] = submission.refused
            continue
        try:
            codes.append(student_code(student.id, submission.files, week))
        except Exception as exc:  # noqa: BLE001 - one submission's text never stops the comparison
            refused[student.id] = shown(f"its code blocks could not be read ({type(exc).__name__}: "
                                        f"{str(exc)[:300]})")
    if not codes and not refused:
        raise SimilarityError(f"{source} has no student folders or .zip files")
    return codes, refused


def run(week: int, source: Path, out: Path, threshold: float = THRESHOLD, common: int | None = None,
        top: int = 10, stream: TextIO | None = None) -> dict:
    """Compare the class in ``source``, write the page and the JSON to ``out``, print the best pairs to
    ``stream`` (if given); returns what similarity.json holds."""
    if not 0 <= threshold <= 1:
        raise SimilarityError(f"--threshold is a share between 0 and 1, not {threshold}")
    if common is not None and common < 2:
        raise SimilarityError(f"--common must be 2 or more, not {common}")
    codes, refused = read_class(source, week, out)
    common = common_limit(len(codes)) if common is None else common
    pairs = compare(codes, handout_blocks(week), max_common=common)
    meta = {"week": week, "threshold": threshold, "k": K, "window": WINDOW, "common": common,
            "handout": handout_source(week)}
    report = report_json(pairs, codes, refused, meta)
    out.mkdir(parents=True, exist_ok=True)
    write_atomic(out / "similarity.html", similarity_html(pairs, codes, refused, meta))
    write_json(out / "similarity.json", report)
    if stream is not None:
        print_top(pairs, threshold, stream, top)
        print(f"  page: {printable(out / 'similarity.html', multiline=False)} and similarity.json",
              file=stream)
    return report


def main(argv: list[str]) -> int:
    """``grade similarity ...`` (argv without the word ``similarity``)."""
    args = _parser().parse_args(argv)
    try:
        week = get_week(args.week).number
        out = Path(args.out) if args.out else Path("reports") / f"similarity-week{week}"
        run(week, Path(args.source), out, args.threshold, args.common, args.top, sys.stdout)
    except (SimilarityError, ValueError, OSError) as exc:
        print(f"grade similarity: {printable(str(exc), multiline=False)}", file=sys.stderr)
        return 2
    return 0
