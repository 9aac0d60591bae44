"""Seconds to grade one submission (the reference solutions), wall and CPU, with a baseline from the same run.

    python benchmarks/grade_bench.py [--repeat 3] [--weeks 1 2 3 4] [--cli-week 3] [--no-hidden] [--report]
                                     [--sandbox auto|bwrap|subprocess]

Measures the baseline (a fresh `python -c 'import grader.grading'` plus a bare sandboxed worker start, see
grading_baseline.py) before and after the runs and divides by their mean, saying how far the two are apart (on
a shared machine the speed drifts: a 15 % change is flagged). Each run is also paired with one baseline
measured just before it, and the median of the runs' ratios to their own baseline is printed ("paired"): the
figure that holds when the machine's speed drifts within the benchmark. The runs: `grade weekN --solutions` as
a user runs it (a fresh process: imports, splicing, the worker, every check, the HTML report), and
grade_submission per week in this already-warm process, visible checks and with --hidden (without the report,
unless --report: then each also writes its JSON and HTML report, as `grade weekN` does). Each figure in wall
and CPU seconds (all processes: the grader and its sandboxed workers) and as a ratio to the baseline. A figure
to read, not a test: on a shared machine compare CPU seconds and the ratios, not wall seconds.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from grading_baseline import Baseline, drift_line, measure_baseline, paired, pooled

from grader.grading import grade_submission
from grader.sandbox.errors import SandboxUnavailable
from simiam.course.weeks import week_numbers
from simiam.machine import (
    Stopwatch,
    Usage,
    load_after_line,
    machine_line,
    median_usage,
    prepare_bytecode,
    ratio,
)

ROOT = Path(__file__).resolve().parents[1]
_CLI = "import sys; from grader.cli import main; sys.exit(main())"  # what the `grade` script runs


def cli_run(week: int, sandbox: str) -> Usage:
    """`grade weekN --solutions` in a fresh process, report written into a temporary folder."""
    with tempfile.TemporaryDirectory(prefix="simiam-bench-") as out, Stopwatch() as sw:
        done = subprocess.run([sys.executable, "-c", _CLI, f"week{week}", "--solutions", "--out", out,
                               "--sandbox", sandbox], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              text=True)
    if done.returncode != 0:
        raise SystemExit(f"grade week{week} --solutions failed ({done.returncode}): {done.stderr[-2000:]}")
    return sw.usage


def _figure(label: str, usages: list[Usage], ratios: list[float], base: Baseline, extra: str = "") -> str:
    u = median_usage(usages)
    return (f"{label}: wall {u.wall:.2f} s median ({min(x.wall for x in usages):.2f} best), "
            f"CPU {u.cpu:.2f} s ({u.cpu_self:.2f} in this process + {u.cpu_children:.2f} in children) = "
            f"{ratio(u.wall, base.total.wall):.1f}x baseline wall, "
            f"{ratio(u.cpu, base.total.cpu):.1f}x baseline CPU, paired {statistics.median(ratios):.1f}x "
            f"({', '.join(f'{r:.1f}' for r in ratios)}){extra}")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=3, help="runs per figure (the median is printed)")
    p.add_argument("--weeks", type=int, nargs="+", default=list(week_numbers()), choices=week_numbers())
    p.add_argument("--cli-week", type=int, default=3, choices=week_numbers(),
                   help="the week graded as a fresh `grade` process")
    p.add_argument("--no-hidden", action="store_true", help="skip the --hidden figures")
    p.add_argument("--report", action="store_true",
                   help="the warm gradings also write their JSON and HTML report (as `grade weekN` does)")
    p.add_argument("--sandbox", default="auto", choices=["auto", "bwrap", "subprocess"])
    args = p.parse_args(argv)
    if args.repeat < 1:
        p.error("--repeat must be at least 1")
    bytecode = prepare_bytecode()
    try:
        base = measure_baseline(args.sandbox, week=args.cli_week, runs=max(3, args.repeat))
    except SandboxUnavailable as exc:
        print(f"--sandbox {args.sandbox}: {exc}", file=sys.stderr)
        return 2
    print(machine_line(base.sandbox), flush=True)
    print(bytecode, flush=True)
    figures: list[tuple[str, list[Usage], list[float], str]] = []  # printed at the end
    runs, ratios = [], []
    for _ in range(args.repeat):
        base_now = paired(args.sandbox, args.cli_week)
        runs.append(cli_run(args.cli_week, args.sandbox))
        ratios.append(ratio(runs[-1].cpu, base_now.cpu))
    figures.append((f"grade week{args.cli_week} --solutions (fresh process)", runs, ratios, ""))
    for hidden in (False, True) if not args.no_hidden else (False,):
        for week in args.weeks:
            usages, ratios, checks = [], [], []
            for _ in range(args.repeat):
                base_now = paired(args.sandbox, args.cli_week)
                with tempfile.TemporaryDirectory(prefix="simiam-bench-") as out, Stopwatch() as sw:
                    result = grade_submission(week, ROOT / "solutions" / f"week{week}", seed=2014,
                                              hidden=hidden, sandbox=args.sandbox,
                                              out_dir=Path(out) if args.report else None)
                usages.append(sw.usage)
                ratios.append(ratio(sw.usage.cpu, base_now.cpu))
                checks.append(sum(result["timing"]["checks"].values()))
            extra = (f"; checks {statistics.median(checks):.2f} s, {len(result['checks'])} checks, score "
                     f"{result['score']:g}/{result['max_score']:g}, isolation {result.get('isolation', '?')}")
            label = (f"week{week} {'hidden ' if hidden else 'visible'} grade_submission "
                     f"{'and its report ' if args.report else ''}(warm process)")
            figures.append((label, usages, ratios, extra))
    after = measure_baseline(args.sandbox, week=args.cli_week, runs=max(3, args.repeat))
    both = pooled(base, after)
    print("\n".join(both.lines()))
    print(drift_line(base, after))
    for label, usages, ratios, extra in figures:
        print(_figure(label, usages, ratios, both, extra))
    print(load_after_line())
    return 0


if __name__ == "__main__":
    sys.exit(main())
