"""The `grade` command: grade one week's submission (or every week, or a batch) and print the checks.

    grade week3                      # ./assignments/week3, visible checks, reports/week3.{json,html}
    grade week3 path/to/folder --seed 7 --out feedback/
    grade week2 --check week2.uni_to_diff.round_trip --case 'v=0.1,w=-2.0'   # replay one failing case
    grade week3 --solutions --hidden # the reference solutions, with the instructor's hidden checks
    grade week4 --practice           # the hidden checks on the practice variants (not graded)
    grade all                        # every week
    grade week3 --batch submissions/ --jobs 4 --out graded/   # official: hidden checks, secret seed
    grade week3 path/to/alice --hidden --seed graded/          # one student with that batch's hidden set
    grade week3 --batch CS101-HW3_submissions.zip --roster gradebook.csv --deadline 2026-03-01T23:59-05:00 \
        --late-penalty 10%/day --late-cap 50%   # a Canvas, Moodle or Gradescope download as it comes
    grade handout week3 --out release/   # and: grade package gradescope|prairielearn|coursera weekN,
                                         #      grade selfcheck
    grade similarity week3 submissions/ --out graded/   # pairs of students whose code blocks look alike

Exit status: 0 every check passed, 1 some check did not (a practice check too, with --practice), 2 the
command itself could not run.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable
from pathlib import Path

from grader.grading import DEFAULT_SEED, CourseFilesMissing, grade_submission, write_outputs
from grader.platforms.cli import PLATFORMS
from grader.result import all_passed
from grader.sandbox.capabilities import has_module
from grader.terminal import print_result
from grader.untrusted import printable
from simiam import safe_write
from simiam.course.folders import WeekFolderNotFound, week_folder
from simiam.course.weeks import get_week, week_numbers

__all__ = ["main", "print_result"]
PLATFORM_COMMANDS = ("handout", "package", "selfcheck")   # grader.platforms.cli parses these


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="grade", description="Grade a Control of Mobile Robots (QuickBot) assignment.",
        epilog=f"Instructors: grade handout weekN, grade package {'|'.join(PLATFORMS)} weekN, "
               "grade selfcheck (grade handout --help, ...; see docs/platforms.md); grade similarity weekN "
               "SOURCE: similar code blocks in a class (docs/batch.md).",
    )
    p.add_argument("week", help=f"week{min(week_numbers())} .. week{max(week_numbers())}, or all")
    p.add_argument("path", nargs="?", default=None, help="submission folder (default: the current folder "
                   "if named weekN, else ./weekN, else ./assignments/weekN)")
    p.add_argument("--solutions", action="store_true", help="grade solutions/weekN (the reference solutions)")
    p.add_argument(
        "--out",
        default=None,
        help="folder for weekN.json and weekN.html (default ./reports; with --batch ./reports/batch-weekN)",
    )
    p.add_argument("--json", dest="json_file", default=None, help="also write the result JSON to this file")
    p.add_argument(
        "--seed", default=None, metavar="N|FOLDER",
        help=f"fixes every random choice (default {DEFAULT_SEED}; with --batch a secret one kept in --out); "
             "a batch output folder or its .seed file means that batch's seed",
    )
    p.add_argument("--hidden", action="store_true",
                   help="also run the hidden checks (official grading; a --batch always does, unless "
                        "--visible-only)")
    p.add_argument("--practice", action="store_true",
                   help="also run the hidden checks on the practice variants shipped with the course (weeks "
                        "3-7): drawn like the hidden ones but never them; shown apart, never part of the "
                        "score")
    p.add_argument("--check", default=None, help="run only this check id, e.g. week3.pid.integral")
    p.add_argument("--case", default=None, help="with --check: replay one case, e.g. 'v=0.1,w=-2.0'")
    p.add_argument(
        "--sandbox",
        default="auto",
        choices=("auto", "bwrap", "subprocess"),
        help="how student code is isolated (default: bubblewrap when it works)",
    )
    batch = p.add_argument_group("batch grading (official: hidden checks and the output folder's secret "
                                 "seed)")
    batch.add_argument("--batch", default=None, metavar="SOURCE",
                       help="grade every submission in SOURCE: a folder with one sub-folder or .zip per "
                            "student id, or Canvas's submissions zip, Moodle's download or Gradescope's "
                            "export (the .zip as downloaded or its extracted folder), recognised by its"
                            " layout")
    batch.add_argument("--visible-only", action="store_true",
                       help="grade the batch with the visible checks only (not official grades)")
    batch.add_argument("--only", default=None, metavar="ID[,ID...]",
                       help="regrade these students, even when unchanged, and no one else")
    batch.add_argument("--canvas-assignment", default=None, metavar="TITLE",
                       help='the Canvas gradebook column of canvas_import.csv, e.g. "Week 3 (4411)"')
    batch.add_argument(
        "--jobs", type=int, default=None, help="submissions graded at once (default: the number of cores)"
    )
    batch.add_argument(
        "--timeout", type=float, default=None, help="seconds one submission may take in all (default 300)"
    )
    batch.add_argument("--force", action="store_true", help="regrade what is already graded")
    batch.add_argument("--quiet", action="store_true", help="no progress bar")
    batch.add_argument("--executor", default="local", choices=("local", "dask"),
                       help="where the submissions are graded: local (--jobs processes on this machine, the "
                            "default) or dask (the workers of the Dask cluster at --scheduler)")
    batch.add_argument("--scheduler", default=None, help="Dask scheduler address (with --executor dask)")
    batch.add_argument("--similarity", action="store_true",
                       help="after grading, also write similarity.html: pairs of students whose code blocks "
                            "look alike (as grade similarity weekN SOURCE)")
    late = p.add_argument_group("roster and late work (with --batch; see docs/batch.md)")
    late.add_argument("--roster", default=None, metavar="CSV",
                      help="the class list: id, name, login/email, section, extension columns (a Canvas "
                           "gradebook export, Moodle's grading worksheet, Gradescope's roster work as they "
                           "come); names who did not submit")
    late.add_argument("--deadline", default=None, metavar="ISO",
                      help="the due date, ISO 8601 with its offset (2026-03-01T23:59-05:00), or with "
                           "--timezone")
    late.add_argument("--late-penalty", default=None, metavar="RATE",
                      help="percent of the points possible per day or hour late, rounded up: 10%%/day, "
                           "2%%/hour")
    late.add_argument("--late-cap", default=None, metavar="PCT", help="the penalty is at most this: 50%%")
    late.add_argument("--late-floor", default=None, metavar="PCT",
                      help="as Canvas's lowest possible grade: lateness never takes a score below this share")
    late.add_argument("--grace", default=None, metavar="DURATION",
                      help="this long past the deadline is not late: 15m, 1h (a bare number is minutes)")
    late.add_argument("--times", default=None, metavar="CSV",
                      help="submission times where the download has none (Canvas, Moodle): id and "
                           "submitted_at columns, or Moodle's grading worksheet")
    late.add_argument("--file-times", action="store_true",
                      help="use the files' own times as submission times where nothing else gives one (only "
                           "when you know they are: Canvas's download dates its entries when it was zipped)")
    late.add_argument("--timezone", default=None, metavar="ZONE",
                      help="time zone of dates given without one (Moodle's worksheet): Europe/London")
    return p


def _week(text: str) -> int:
    """The number of a declared week (ValueError naming the weeks there are, or all)."""
    try:
        return get_week(text).number
    except ValueError as exc:
        raise ValueError(f"{exc}, or all") from None


def _folder(args: argparse.Namespace, week: int, many: bool) -> Path:
    """PATH (PATH/weekN for `grade all`), solutions/weekN, or the default rule (simiam.course.folders)."""
    path = Path(args.path) / f"week{week}" if many and args.path else args.path
    return week_folder(week, path, solutions=args.solutions)


def practice_weeks() -> tuple[int, ...]:
    """The weeks `--practice` runs a practice set for (`grade all --practice` grades the others plainly)."""
    from grader.practice import WEEKS_WITH_PRACTICE, load_practice

    return tuple(w for w in WEEKS_WITH_PRACTICE if load_practice(w) is not None)


def _grade_one(args: argparse.Namespace, week: int, many: bool) -> int:
    from grader.properties import parse_case

    try:
        folder = _folder(args, week, many)
    except WeekFolderNotFound as exc:
        print(f"grade: {printable(exc)} (grade week{week} PATH)", file=sys.stderr)
        return 2
    if not folder.is_dir():
        print(f"grade: no such folder: {printable(folder, multiline=False)}", file=sys.stderr)
        return 2
    case = parse_case(args.case) if args.case else None
    shown = "--solutions" if args.solutions else str(folder)
    traces: dict[str, dict] = {}
    # a replay of one check prints its answer and leaves the full report of the last grading alone
    out_dir = None if args.check else Path(args.out or "reports")
    result = grade_submission(
        week,
        folder,
        seed=DEFAULT_SEED if args.seed is None else args.seed,
        hidden=args.hidden,
        sandbox=args.sandbox,
        only=args.check,
        case=case,
        replay_prefix=f"grade week{week} {shown}",
        traces=traces,
        practice=args.practice and week in practice_weeks(),
    )
    print_result(result)
    if case is not None:
        from grader.replay import print_replay

        print_replay(result)
    # written here, not by grade_submission, so that a file that cannot be written (a link planted in the
    # student's reports/, which is never written through) is one line after the grades, not a traceback
    written = True
    if out_dir is not None and (written := _written(lambda: write_outputs(result, traces, out_dir))):
        print(f"  report: {printable(out_dir / f'week{week}.html', multiline=False)} and week{week}.json")
    if args.json_file:
        text = json.dumps(result, indent=1)
        written = _written(lambda: safe_write.write_text(args.json_file, text)) and written
    if not written:
        return 2
    practice = result.get("practice")
    practised = not isinstance(practice, dict) or all(
        c.get("status") == "passed" for c in practice.get("checks") or [] if isinstance(c, dict))
    return 0 if all_passed(result) and practised else 1


def _written(write: Callable[[], object]) -> bool:
    """Run `write`; False, with the reason printed, if the file system refused it."""
    try:
        write()
    except OSError as exc:
        print(f"grade: not written: {printable(str(exc), multiline=False)}", file=sys.stderr)
        return False
    return True


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `grade` console script."""
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] in PLATFORM_COMMANDS:
        from grader.platforms.cli import main as platforms_main

        return platforms_main(argv)
    if argv and argv[0] == "similarity":
        from grader.similarity.command import main as similarity_main

        return similarity_main(argv[1:])
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        weeks = list(week_numbers()) if args.week.lower() == "all" else [_week(args.week)]
        if args.seed is not None:
            from grader.batch.seed import parse_seed

            args.seed = parse_seed(args.seed)
        if args.visible_only and not args.batch:
            raise ValueError("--visible-only is for --batch (a single grading runs the visible checks "
                             "unless --hidden)")
        if args.case and not args.check:
            raise ValueError("--case needs --check ID (the check whose case you replay)")
        if args.practice:
            if args.hidden or args.batch:
                raise ValueError("--practice is for one submission without --hidden: it runs the practice "
                                 "variants in place of the hidden ones (official grading runs those)")
            if len(weeks) == 1:
                from grader.practice import missing_practice_set

                missing_practice_set(weeks)
        if args.hidden or (args.batch and not args.visible_only):
            from grader.hidden import missing_hidden_set

            try:
                missing_hidden_set(weeks)  # a student install: say so, rather than show the checks as errors
            except ValueError as exc:
                if args.batch:
                    raise ValueError(f"{exc} A batch is official grading, which runs them; "
                                     "--visible-only grades the class without them (not official "
                                     "grades).") from None
                raise
        if args.batch:
            if len(weeks) != 1:
                raise ValueError("--batch grades one week at a time")
            if not has_module("fcntl"):  # its store locks files with fcntl, its pool passes descriptors
                raise ValueError("--batch (grading a whole class) needs Linux or macOS; on Windows run it "
                                 "in WSL (Windows Subsystem for Linux). Grading one submission works here.")
            from grader.batch.runner import main as batch_main

            args.week_number = weeks[0]
            return batch_main(args)
        codes = [_grade_one(args, week, many=len(weeks) > 1) for week in weeks]
    except (ValueError, CourseFilesMissing) as exc:
        print(f"grade: {printable(exc)}", file=sys.stderr)
        return 2
    except ImportError as exc:
        print(f"grade: this part of the grader is not installed ({exc})", file=sys.stderr)
        return 2
    return max(codes)


if __name__ == "__main__":
    sys.exit(main())
