"""`grade handout | package | selfcheck`: the instructor's release and platform commands (parsing only).

    grade handout week3 --out release/
    grade package gradescope week3 --out autograder.zip [--seed N] [--hidden-visibility after_published]
    grade package prairielearn week3 --out pl-week3/ [--seed N] [--image NAME] [--timeout S]
    grade package coursera week3 --out coursera-week3/ [--seed N] [--part-id ID]
    grade selfcheck [--course DIR] [--weeks 2,3] [--jobs N]

Exit status: 0 done (selfcheck: every expectation held), 1 selfcheck found a problem, 2 the command could
not run (bad arguments, no course checkout, a leak in a handout, a failed wheel build).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from simiam.course.weeks import get_week, week_numbers

COMMANDS = ("handout", "package", "selfcheck")
PLATFORMS = ("gradescope", "prairielearn", "coursera")  # `grade package PLATFORM`; grade --help lists them


def _week(text: str) -> int:
    """The number of a declared week (argparse's error names the weeks there are)."""
    try:
        return get_week(text).number
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="grade", description="Release the weeks and grade them on a platform.")
    sub = p.add_subparsers(dest="command", required=True)
    h = sub.add_parser("handout", help="the folder and zip students download for a week")
    h.add_argument("week", type=_week)
    h.add_argument("--out", type=Path, required=True, help="folder that receives weekN/ and weekN.zip")
    h.add_argument("--course", type=Path, default=None, help="the course checkout (default: here)")
    k = sub.add_parser("package", help="an autograder for Gradescope, PrairieLearn or Coursera")
    k.add_argument("platform", choices=PLATFORMS)
    k.add_argument("week", type=_week)
    k.add_argument("--out", type=Path, required=True,
                   help="gradescope: the zip to write; prairielearn, coursera: a new folder")
    k.add_argument("--course", type=Path, default=None, help="the course checkout (default: here)")
    k.add_argument("--seed", type=int, default=None,
                   help="the secret seed of official grading (default: a fresh random one, printed)")
    k.add_argument("--hidden-visibility", default="after_published",
                   choices=("hidden", "after_due_date", "after_published", "visible"),
                   help="Gradescope: when students see the hidden checks (default after_published)")
    k.add_argument("--image", default=None, help="PrairieLearn: the grader image name (default simiam-weekN)")
    k.add_argument("--timeout", type=int, default=120, help="PrairieLearn: seconds per grading job (max 600)")
    k.add_argument("--part-id", default=None,
                   help="Coursera: the assignment part this grader grades (default: any part)")
    s = sub.add_parser("selfcheck", help="solutions, stubs and kept wrong versions grade as meant")
    s.add_argument("--course", type=Path, default=None, help="the course checkout (default: here)")
    s.add_argument("--weeks", default=None, help="comma-separated weeks (default: every week of the course)")
    s.add_argument("--wrong", type=Path, default=None,
                   help="folder of wrong versions (default COURSE/tests/data/wrong)")
    s.add_argument("--seed", type=int, default=None, help="grading seed (default the grader's)")
    return p


def main(argv: list[str]) -> int:
    """Run one of COMMANDS; `argv` starts with the command name."""
    from grader.platforms.course import CourseNotFound, course_root
    from grader.platforms.handout import HandoutLeak
    from grader.platforms.wheel import WheelBuildFailed
    from simiam.safe_write import LinkRefused

    args = _parser().parse_args(argv)
    try:
        course = course_root(args.course)
        if args.command == "handout":
            from grader.platforms.handout import build_handout

            folder, archive = build_handout(args.week, args.out, course)
            print(f"handout of week {args.week}: {folder}/ and {archive}")
            return 0
        if args.command == "package":
            return _package(args, course)
        from grader.platforms.selfcheck import run_selfcheck

        weeks = ([_week(w.strip()) for w in args.weeks.split(",") if w.strip()] if args.weeks is not None
                 else list(week_numbers()))
        return run_selfcheck(course, weeks, wrong=args.wrong, seed=args.seed)
    except (CourseNotFound, HandoutLeak, WheelBuildFailed, ValueError, argparse.ArgumentTypeError,
            LinkRefused) as exc:  # LinkRefused: a link where a file was to be written (simiam.safe_write)
        print(f"grade {args.command}: {exc}", file=sys.stderr)
        return 2


def _package(args: argparse.Namespace, course: Path) -> int:
    from grader.platforms.bundle import new_seed

    seed = args.seed if args.seed is not None else new_seed()
    if args.platform == "gradescope":
        from grader.platforms import gradescope

        if args.out.suffix.lower() != ".zip":
            raise ValueError(f"--out {args.out}: Gradescope takes a .zip")
        config = gradescope.build(args.week, args.out, course, seed, args.hidden_visibility)
        where = args.out
    elif args.platform == "coursera":
        from grader.platforms import coursera

        config = coursera.build(args.week, args.out, course, seed, part_id=args.part_id)
        where = f"{args.out}/ (zip its contents for Coursera's grader upload, or docker build it)"
    else:
        from grader.platforms import prairielearn

        config = prairielearn.build(args.week, args.out, course, seed, image=args.image, timeout=args.timeout)
        where = f"{args.out}/ (question/ for the course repository, image/ for docker build)"
    print(f"week {args.week} for {args.platform}: {where}")
    print(f"  {config['checks']} checks, {config['hidden_checks']} hidden, "
          f"max score {config['max_score']:g}; wheel {config['wheel']}")
    if args.seed is None:
        print(f"  secret seed {seed} (keep it to rebuild the same grading: --seed {seed})")
    return 0
