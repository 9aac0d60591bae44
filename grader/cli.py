"""The `grade` command: grade one week's submission (or every week, or a batch) and print the checks.

    grade week3                      # ./assignments/week3, visible checks, reports/week3.{json,html}
    grade week3 path/to/folder --seed 7 --out feedback/
    grade week2 --check week2.uni_to_diff.round_trip --case 'v=0.1,w=-2.0'   # replay one failing case
    grade week3 --solutions --hidden # the reference solutions, with the instructor's hidden checks
    grade all                        # every week
    grade week3 --batch submissions/ --jobs 4 --out graded/

Exit status: 0 every check passed, 1 some check did not, 2 the command itself could not run.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import textwrap
from pathlib import Path

from grader.grading import DEFAULT_SEED, CourseFilesMissing, grade_submission
from grader.result import all_passed
from simiam.course.folders import WeekFolderNotFound, week_folder

WEEKS = (1, 2, 3, 4)
_MARK = {"passed": "ok", "failed": "FAIL", "error": "ERROR", "timeout": "TIMEOUT"}


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="grade", description="Grade a Control of Mobile Robots (QuickBot) assignment."
    )
    p.add_argument("week", help="week1 .. week4, or all")
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
        "--seed", type=int, default=DEFAULT_SEED, help=f"fixes every random choice ({DEFAULT_SEED})"
    )
    p.add_argument("--hidden", action="store_true", help="also run the hidden checks (official grading)")
    p.add_argument("--check", default=None, help="run only this check id, e.g. week3.pid.integral")
    p.add_argument("--case", default=None, help="with --check: replay one case, e.g. 'v=0.1,w=-2.0'")
    p.add_argument(
        "--sandbox",
        default="auto",
        choices=("auto", "bwrap", "subprocess"),
        help="how student code is isolated (default: bubblewrap when it works)",
    )
    batch = p.add_argument_group("batch grading (one sub-folder or .zip per student)")
    batch.add_argument("--batch", default=None, metavar="DIR", help="grade every submission in DIR")
    batch.add_argument(
        "--jobs", type=int, default=None, help="submissions graded at once (default: the number of cores)"
    )
    batch.add_argument(
        "--timeout", type=float, default=None, help="seconds one submission may take in all (default 300)"
    )
    batch.add_argument("--force", action="store_true", help="regrade what is already graded")
    batch.add_argument("--quiet", action="store_true", help="no progress bar")
    batch.add_argument("--executor", default="local", choices=("local", "dask"))
    batch.add_argument("--scheduler", default=None, help="Dask scheduler address (with --executor dask)")
    return p


def _week(text: str) -> int:
    number = text.lower().removeprefix("week")
    if not number.isdigit() or int(number) not in WEEKS:
        raise ValueError(f"unknown week {text!r}: use week1, week2, week3, week4 or all")
    return int(number)


def _folder(args: argparse.Namespace, week: int, many: bool) -> Path:
    """PATH (PATH/weekN for `grade all`), solutions/weekN, or the default rule (simiam.course.folders)."""
    path = Path(args.path) / f"week{week}" if many and args.path else args.path
    return week_folder(week, path, solutions=args.solutions)


def print_result(result: dict, out=sys.stdout) -> None:
    """The terminal table: one line per check, the total, and what a student should know next."""
    width = max(100, shutil.get_terminal_size((120, 20)).columns)
    isolation = result.get("isolation", "?")
    print(
        f"week {result['week']}: {result['submission']}  (seed {result['seed']}, "
        f"grader {result['grader_version']}, isolation {isolation})",
        file=out,
    )
    if result["status"] == "invalid":
        print(f"  INVALID: {result.get('message', '')}", file=out)
    id_width = max([len(c["id"]) for c in result["checks"]] + [10])
    indent = " " * 10
    for c in result["checks"]:
        mark = _MARK.get(c["status"], c["status"])
        hidden = "  [hidden]" if c.get("visibility") == "hidden" else ""
        print(f"  {mark:7s} {c['id']:{id_width}s} {c['points']:5.2f}/{c['max_points']:<4g}{hidden}", file=out)
        for line in textwrap.wrap(c["message"], width - len(indent)):
            print(indent + line, file=out)
        replay = (c.get("details") or {}).get("replay")
        if replay and c["status"] != "passed":
            print(f"{indent}replay: {replay}", file=out)
    print(f"  total: {result['score']:g} / {result['max_score']:g}", file=out)
    for note in result.get("notices", []):
        print(f"  note: {note}", file=out)
    if not result.get("hidden"):
        n = result.get("hidden_checks_not_run", 0)
        ran = result.get("visible_checks", len(result["checks"]))
        print(
            f"  {_count(ran, 'visible check')} ran here"
            + (f"; {_count(n, 'hidden check')} (other goals, other worlds, drawn per seed) run at official "
               "grading" if n else ""),
            file=out,
        )


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}{'' if n == 1 else 's'}"


def _grade_one(args: argparse.Namespace, week: int, many: bool) -> int:
    from grader.properties import parse_case

    try:
        folder = _folder(args, week, many)
    except WeekFolderNotFound as exc:
        print(f"grade: {exc} (grade week{week} PATH)", file=sys.stderr)
        return 2
    if not folder.is_dir():
        print(f"grade: no such folder: {folder}", file=sys.stderr)
        return 2
    case = parse_case(args.case) if args.case else None
    shown = "--solutions" if args.solutions else str(folder)
    traces: dict[str, dict] = {}
    # a replay of one check prints its answer and leaves the full report of the last grading alone
    out_dir = None if args.check else Path(args.out or "reports")
    result = grade_submission(
        week,
        folder,
        seed=args.seed,
        hidden=args.hidden,
        out_dir=out_dir,
        sandbox=args.sandbox,
        only=args.check,
        case=case,
        replay_prefix=f"grade week{week} {shown}",
        traces=traces,
    )
    print_result(result)
    if case is not None:
        from grader.replay import print_replay

        print_replay(result)
    if out_dir is not None:
        print(f"  report: {out_dir / f'week{week}.html'} and week{week}.json")
    if args.json_file:
        Path(args.json_file).write_text(json.dumps(result, indent=1), encoding="utf-8")
    return 0 if all_passed(result) else 1


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `grade` console script."""
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        weeks = list(WEEKS) if args.week.lower() == "all" else [_week(args.week)]
        if args.case and not args.check:
            raise ValueError("--case needs --check ID (the check whose case you replay)")
        if args.batch:
            if len(weeks) != 1:
                raise ValueError("--batch grades one week at a time")
            from grader.batch.runner import main as batch_main

            args.week_number = weeks[0]
            return batch_main(args)
        codes = [_grade_one(args, week, many=len(weeks) > 1) for week in weeks]
    except (ValueError, CourseFilesMissing) as exc:
        print(f"grade: {exc}", file=sys.stderr)
        return 2
    except ImportError as exc:
        print(f"grade: this part of the grader is not installed ({exc})", file=sys.stderr)
        return 2
    return max(codes)


if __name__ == "__main__":
    sys.exit(main())
