"""The `simiam` command: run a week's scenario, migrate last week's blocks, benchmark the simulator."""

from __future__ import annotations

import argparse
import sys

from simiam.course.weeks import week_numbers


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="simiam", description="Sim.I.am QuickBot simulator (Python port)")
    sub = p.add_subparsers(dest="command", required=True)
    weeks = week_numbers()

    run = sub.add_parser("run", help="run a week's scenario headless and write a trace and a replay page")
    run.add_argument("week", help=f"week{weeks[0]} .. week{weeks[-1]}")
    run.add_argument("path", nargs="?", default=None, help="submission folder (default: the current folder "
                     "if named weekN, else ./weekN, else ./assignments/weekN)")
    run.add_argument("--solutions", action="store_true", help="use solutions/weekN")
    run.add_argument("--seconds", type=float, default=None, help="simulated time (default: the week's)")
    run.add_argument("--dt", type=float, default=None,
                     help="time step in seconds (default: the week's, 0.033; the original also ran 0.05)")
    run.add_argument("--out", default="runs", help="output folder (default ./runs)")
    run.add_argument("--world", default=None, help="world file to use instead of the week's")
    run.add_argument("--start", default=None, metavar="X,Y,THETA",
                     help="the robot's start pose instead of the world's: metres and radians; THETA may be "
                          "written with pi, e.g. --start 0,0,pi or --start=-0.5,0.2,-pi/2")

    mig = sub.add_parser("migrate", help="carry your filled blocks from last week's folder into this week's")
    mig.add_argument("week", help="the week to migrate into, e.g. week3")
    mig.add_argument("--from", dest="source", required=True,
                     help="last week's folder (a bare weekN is looked for like --to's default)")
    mig.add_argument("--to", dest="target", default=None, help="this week's folder (default: the current "
                     "folder if named weekN, else ./weekN, else ./assignments/weekN)")
    mig.add_argument("--dry-run", action="store_true", help="say what would move, change nothing")

    bench = sub.add_parser("bench", help="steps per second of one QuickBot in the week-4 world")
    bench.add_argument("--json", action="store_true", help="print one JSON object")
    bench.add_argument("--seconds", type=float, default=None, help="simulated seconds per repetition")
    return p


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `simiam` console script."""
    args = _parser().parse_args(argv)
    if args.command == "run":
        from simiam.run import main as run_main

        return run_main(args)
    if args.command == "migrate":
        from simiam.course.migrate import main as migrate_main

        return migrate_main(args)
    from simiam.bench import main as bench_main

    return bench_main(args)


if __name__ == "__main__":
    sys.exit(main())
