"""``grade similarity weekN SOURCE``: which students' code blocks look alike, for the instructor to read.

    grade similarity week3 submissions/ --out graded-week3/     # next to the batch's summary.html
    grade similarity week3 CS101-HW3_submissions.zip --roster gradebook.csv --out graded-week3/
    grade similarity week3 submissions/ --threshold 0.5 --common 20

SOURCE is what ``grade weekN --batch`` takes, read with the batch's own intake and limits
(grader/similarity/students.py): a class folder or a platform's download as it comes. Writes
``similarity.html`` and ``similarity.json`` to ``--out`` (default ``reports/similarity-weekN``) and prints
the best pairs. Exit status 0 when the report is written (whatever it found), 2 when it could not run.
``grade weekN --batch SOURCE --similarity`` does the same after grading (:func:`after_batch`).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TextIO

from grader.batch.intake import ClassList
from grader.batch.store import write_atomic, write_json
from grader.similarity.compare import MAX_COMMON, common_limit, compare
from grader.similarity.fingerprints import WINDOW, K
from grader.similarity.page import print_top, report_json, similarity_html
from grader.similarity.students import ComparedClass, SimilarityError, read_source, read_students
from grader.similarity.submitted import handout_blocks, handout_source
from grader.untrusted import printable
from simiam.course.weeks import get_week

__all__ = ["THRESHOLD", "SimilarityError", "after_batch", "compare_class", "main", "read_class", "run"]
THRESHOLD = 0.6   # measured: copies 0.70-1.00, independent week-3 solutions at most 0.49 (docs/batch.md)


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="grade similarity",
        description="Compare the students' code blocks (the handout's own text removed) and rank the "
                    "pairs that look alike. It flags pairs; a person decides.")
    p.add_argument("week", help="weekN: the assignment the submissions are for")
    p.add_argument("source", help="what grade weekN --batch takes: a class folder (one sub-folder or .zip "
                                  "per student id) or Canvas's submissions zip, Moodle's download or "
                                  "Gradescope's export as it comes")
    p.add_argument("--out", default=None, help="folder for similarity.html and similarity.json "
                   "(default reports/similarity-weekN; the batch's --out folder is a good place)")
    p.add_argument("--roster", default=None, metavar="CSV",
                   help="the class list, as grade --batch reads it: the roster's names are shown")
    p.add_argument("--threshold", type=float, default=THRESHOLD,
                   help=f"lowest score shown, 0..1 (default {THRESHOLD})")
    p.add_argument("--common", type=int, default=None,
                   help=f"a passage found in more submissions than this counts for nobody (default "
                        f"{MAX_COMMON}, as MOSS, or a tenth of the class, whichever is more)")
    p.add_argument("--top", type=int, default=10, help="pairs printed (default 10)")
    return p


def read_class(source: Path, week: int, out: Path | None = None, roster: Path | None = None) -> ComparedClass:
    """Every student's compared code in SOURCE, and who could not be compared (with why)."""
    return read_students(read_source(source, out, roster), week)


def run(week: int, source: Path, out: Path, threshold: float = THRESHOLD, common: int | None = None,
        top: int = 10, stream: TextIO | None = None, roster: Path | None = None) -> dict:
    """Compare the class in ``source``, write the page and the JSON to ``out``, print the best pairs to
    ``stream`` (if given); returns what similarity.json holds."""
    _check(threshold, common)
    klass = read_source(source, out, roster)
    if stream is not None:
        print(f"reading {printable(klass.described(), multiline=False)}", file=stream)
    return compare_class(klass, week, out, threshold, common, top, stream)


def _check(threshold: float, common: int | None) -> None:
    if not 0 <= threshold <= 1:
        raise SimilarityError(f"--threshold is a share between 0 and 1, not {threshold}")
    if common is not None and common < 2:
        raise SimilarityError(f"--common must be 2 or more, not {common}")


def compare_class(klass: ClassList, week: int, out: Path, threshold: float = THRESHOLD,
                  common: int | None = None, top: int = 10, stream: TextIO | None = None) -> dict:
    """Compare the students of ``klass`` (as the batch's intake read them) and write the report."""
    _check(threshold, common)
    found = read_students(klass, week)
    codes = found.codes
    common = common_limit(len(codes)) if common is None else common
    pairs = compare(codes, handout_blocks(week), max_common=common)
    meta = {"week": week, "threshold": threshold, "k": K, "window": WINDOW, "common": common,
            "handout": handout_source(week), "source": found.source, "unplaced": found.unplaced,
            "unplaced_count": len(klass.unplaced)}
    report = report_json(pairs, codes, found.not_compared, meta, found.names)
    out.mkdir(parents=True, exist_ok=True)
    page = similarity_html(pairs, codes, found.not_compared, meta, found.names)
    write_atomic(out / "similarity.html", page)
    write_json(out / "similarity.json", report)
    if stream is not None:
        print_top(pairs, threshold, stream, top)
        if found.not_compared:
            print(f"  not compared: {len(found.not_compared)} (the page says why)", file=stream)
        print(f"  page: {printable(out / 'similarity.html', multiline=False)} and similarity.json",
              file=stream)
    return report


def after_batch(klass: ClassList, week: int, out: Path, stream: TextIO | None) -> None:
    """``grade weekN --batch SOURCE --similarity``: the report of the class just graded, into the batch's
    ``--out``. Whatever stops it is said on ``stream`` and never costs the batch its results."""
    try:
        if stream is not None:
            print("similarity of the students' code blocks:", file=stream)
        compare_class(klass, week, out, stream=stream)
    except Exception as exc:  # noqa: BLE001 - the grades come first: the batch still writes its class files
        why = str(exc) if isinstance(exc, (SimilarityError, OSError)) else f"{type(exc).__name__}: {exc}"
        print(f"similarity: not written: {printable(why[:500], multiline=False)}",
              file=stream if stream is not None else sys.stderr)


def main(argv: list[str]) -> int:
    """``grade similarity ...`` (argv without the word ``similarity``)."""
    args = _parser().parse_args(argv)
    try:
        week = get_week(args.week).number
        out = Path(args.out) if args.out else Path("reports") / f"similarity-week{week}"
        run(week, Path(args.source), out, args.threshold, args.common, args.top, sys.stdout,
            Path(args.roster) if args.roster else None)
    except (SimilarityError, ValueError, OSError) as exc:
        print(f"grade similarity: {printable(str(exc), multiline=False)}", file=sys.stderr)
        return 2
    return 0
