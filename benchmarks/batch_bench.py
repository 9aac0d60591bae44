"""Batch grading throughput: submissions graded per minute, per week and --jobs, with the real grader.

    python benchmarks/batch_bench.py                      # weeks 3 and 4, --jobs 1 and 2, 8 submissions each
    python benchmarks/batch_bench.py --weeks 3 --jobs 2 --n 20 --kind mixed

Each run grades a fresh class (copies of solutions/weekN, or stubs, or both alternating) from scratch
into a fresh output folder, exactly as ``grade weekN --batch DIR --jobs J --force`` would, grading
processes' start-up included. It prints the machine line, the baseline of grading_baseline.py measured in
the same run (a fresh `python -c 'import grader.grading'` plus a bare sandboxed worker), and per run the
wall and CPU seconds of all processes (grading processes and their sandboxed workers) per submission, with
their ratios to the baseline. It asserts nothing: on a shared machine compare CPU and the ratios.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import tempfile
from pathlib import Path

from chain_stalls import ChainStalls
from grading_baseline import measure_baseline

from grader.sandbox.errors import SandboxUnavailable
from simiam.machine import Stopwatch, load_after_line, machine_line, prepare_bytecode, ratio

ROOT = Path(__file__).resolve().parents[1]


def make_class(folder: Path, week: int, n: int, kind: str) -> None:
    for i in range(n):
        source = "solutions" if kind == "solutions" or (kind == "mixed" and i % 2 == 0) else "assignments"
        shutil.copytree(ROOT / source / f"week{week}", folder / f"student{i:03d}")


def bench(week: int, jobs: int, n: int, kind: str, sandbox: str) -> dict:
    from grader.batch.runner import BatchOptions, default_jobs, run_batch

    with tempfile.TemporaryDirectory(prefix="simiam-bench-") as tmp:
        klass, out = Path(tmp) / "class", Path(tmp) / "out"
        make_class(klass, week, n, kind)
        stalls = ChainStalls()
        with Stopwatch() as sw:
            stalls.start()
            # the visible checks, as the figures quoted in docs/performance.md were measured (a batch's
            # default, official grading, adds the week's hidden checks)
            report = run_batch(BatchOptions(week=week, batch_dir=klass, out=out, seed=2014, jobs=jobs,
                                            quiet=True, force=True, sandbox=sandbox, hidden=False))
            stalled = stalls.stop()
        seconds, cpu = sw.usage.wall, sw.usage.cpu - stalls.own_cpu
        results = [json.loads(p.read_text()) for p in out.glob("student*.json")]
    finished = sorted(r["finished_s"] for r in report["per_student"].values() if "finished_s" in r)
    timings = [r.get("timing", {}) for r in results]
    grading = [t["grade_submission_seconds"] for t in timings if "grade_submission_seconds" in t]
    harness = [t["batch_seconds"] - t["grade_submission_seconds"] for t in timings
               if "grade_submission_seconds" in t and "batch_seconds" in t]
    cores = min(jobs, default_jobs())
    return {"week": week, "jobs": jobs, "n": n, "seconds": seconds, "per_minute": 60 * n / seconds,
            "cpu_per_submission": cpu / n, "wall_per_submission": seconds / n,
            "busy": cpu / (seconds * cores),
            # chain-seconds in which a grading process and its descendants could not run, per submission
            "stalled_s": stalled * seconds * jobs / n,
            # the last results, when fewer gradings than --jobs were left, and after the last one
            "tail_s": finished[-1] - finished[-min(jobs, len(finished))] if finished else float("nan"),
            "end_s": seconds - finished[-1] if finished else float("nan"),
            "graded": report["counts"]["graded"],
            "isolation": sorted({str(r.get("isolation")) for r in results}),
            "grade_s": sum(grading) / len(grading) if grading else float("nan"),
            "overhead_s": sorted(harness)[len(harness) // 2] if harness else float("nan")}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--weeks", type=int, nargs="+", default=[3, 4])
    parser.add_argument("--jobs", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--n", type=int, default=8, help="submissions per run")
    parser.add_argument("--kind", choices=["solutions", "stubs", "mixed"], default="solutions")
    parser.add_argument("--sandbox", default="auto", help="auto | bwrap | subprocess")
    args = parser.parse_args(argv)
    if args.n < 1 or min(args.jobs) < 1:
        parser.error("--n and --jobs must be at least 1")
    bytecode = prepare_bytecode()
    try:
        base = measure_baseline(args.sandbox)
    except SandboxUnavailable as exc:
        print(f"--sandbox {args.sandbox}: {exc}", file=sys.stderr)
        return 2
    print(machine_line(base.sandbox), flush=True)
    print(bytecode, flush=True)
    print("\n".join(base.lines()), flush=True)
    print(f"{'week':>4} {'jobs':>4} {'n':>4} {'seconds':>8} {'subs/min':>9} {'CPU s/sub':>9} {'x base':>6} "
          f"{'wall s/sub':>10} {'x base':>6} {'grade s':>8} {'overhead s':>10} {'busy':>5} "
          f"{'stall s/sub':>11} {'tail s':>6} {'end s':>5}  isolation",
          flush=True)
    for week in args.weeks:
        for jobs in args.jobs:
            row = bench(week, jobs, args.n, args.kind, args.sandbox)
            missing = "" if row["graded"] == row["n"] else f"  (only {row['graded']} graded)"
            print(f"{row['week']:>4} {row['jobs']:>4} {row['n']:>4} {row['seconds']:>8.1f} "
                  f"{row['per_minute']:>9.1f} {row['cpu_per_submission']:>9.2f} "
                  f"{ratio(row['cpu_per_submission'], base.total.cpu):>6.1f} "
                  f"{row['wall_per_submission']:>10.2f} "
                  f"{ratio(row['wall_per_submission'], base.total.wall):>6.1f} "
                  f"{row['grade_s']:>8.2f} {row['overhead_s']:>10.2f} {row['busy']:>5.0%} "
                  f"{row['stalled_s']:>11.3f} {row['tail_s']:>6.2f} {row['end_s']:>5.2f}  "
                  f"{','.join(row['isolation'])}{missing}", flush=True)
    print("CPU s/sub: CPU seconds of all processes per submission; wall s/sub: the run's wall time per "
          "submission (with --jobs 2, half a submission's own time); x base: divided by the baseline; "
          "grade s: mean wall time of grade_submission (HTML report included) per submission; overhead s: "
          "median batch time beyond it (unpacking, pipes, result files; a cold grading process's start-up "
          "counts for its first submission only); busy: CPU seconds of all processes / (wall seconds x "
          "min(jobs, cores)), how much of the cores the batch kept busy (on a shared machine the "
          "neighbours take the rest); stall s/sub: seconds per submission in which a grading process and "
          "everything it started had no thread running or waiting for a core (benchmarks/chain_stalls.py: "
          "idle the batch itself causes; waiting for a core taken by others does not count); "
          "tail s: from the result that left fewer gradings than --jobs "
          "running to the last result; end s: after the last result (class files, processes "
          "stopping)")
    print(load_after_line())
    return 0


if __name__ == "__main__":
    sys.exit(main())
