"""The pages of a class: a batch of 400 students' real report pages, its size on disk and pages per second.

    python benchmarks/pages_bench.py                    # week 5, 400 students, --jobs 2
    python benchmarks/pages_bench.py --week 3 --n 40 --jobs 1

The course's solution and stub of the week are graded once, for real (hidden checks, seed 2014); a class of
`--n` students is then built by `grade weekN --batch`'s own runner from copies of those two gradings
(alternating), each student's pages rendered for real by the batch's report code (the report, its replay
pages, the shared assets, the class files). Grading itself is left out: what is measured is the pages.
The same run builds the same class as self-contained pages (every replay embedded in the report, as
`grade weekN` writes one report and as a batch wrote them before the pages shared their assets): that
is the baseline, and the ratios compare with it. Printed: the machine line, per layout the total size of
the output folder, the mean and largest student page, the replay pages, pages per second (students whose
pages were written, per wall second) and CPU seconds per student. It asserts nothing.
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from grader.batch.names import student_stem
from simiam.machine import Stopwatch, load_after_line, machine_line, prepare_bytecode, ratio

ROOT = Path(__file__).resolve().parents[1]
GRADINGS = "SIMIAM_PAGES_BENCH_GRADINGS"   # the folder holding the real gradings (for the grading processes)


def grade_once(week: int, folder: Path) -> list[Path]:
    """The week's solution and stub graded for real (hidden checks), with their traces, as JSON files."""
    from grader.grading import grade_submission

    paths = []
    for source in SOURCES:
        traces: dict[str, dict] = {}
        result = grade_submission(week=week, submission=ROOT / source / f"week{week}", seed=2014, hidden=True,
                                  traces=traces)
        path = folder / f"{source}.json"
        path.write_text(json.dumps({"result": result, "traces": traces}))
        paths.append(path)
    return paths


SOURCES = ("solutions", "assignments")     # student i gets the grading of SOURCES[i % 2]


@functools.cache
def _grading(source: str) -> str:
    return (Path(os.environ[GRADINGS]) / f"{source}.json").read_text()


def _copy(task: dict) -> tuple[dict, dict]:
    """The real grading of this student's files (by the number in their id), as a fresh copy."""
    grading = json.loads(_grading(SOURCES[int(task["student"][-3:]) % 2]))
    return grading["result"], grading["traces"]


def shared_pages(task: dict) -> dict:
    """The batch's grading function with the grading replaced by a copy: the report with its replay pages
    (what grader.batch.task writes today)."""
    from grader.batch.pages import ASSETS_FROM_REPLAY, replay_folder
    from grader.report.html import render_report_pages

    result, traces = _copy(task)
    page, replays = render_report_pages(result, traces, folder=replay_folder(student_stem(task["student"])),
                                        assets=ASSETS_FROM_REPLAY)
    return {"result": result, "html": page, "replays": replays}


def self_contained_pages(task: dict) -> dict:
    """The baseline: each report with every replay embedded (one file per student)."""
    from grader.report.html import render_report

    result, traces = _copy(task)
    return {"result": result, "html": render_report(result, traces)}


def build(week: int, n: int, jobs: int, grade_fn: str, folder: Path) -> dict:
    """A class of `n` built into `folder`/out with `grade_fn`: its sizes and speed."""
    from grader.batch.runner import BatchOptions, run_batch

    klass, out = folder / "class", folder / "out"
    for i in range(n):   # the files of the grading each student gets a copy of (_copy), as a class sends them
        source = SOURCES[i % 2]
        shutil.copytree(ROOT / source / f"week{week}", klass / f"student{i:03d}")
    with Stopwatch() as sw:
        report = run_batch(BatchOptions(week=week, batch_dir=klass, out=out, seed=2014, jobs=jobs, quiet=True,
                                        force=True, hidden=True), grade_fn=grade_fn)
    files = [p for p in out.rglob("*") if p.is_file()]
    pages = [p.stat().st_size for p in out.glob("student*.html")]
    replays = [p.stat().st_size for p in out.glob("replays/*/*.html")]
    return {"graded": report["counts"]["graded"], "seconds": sw.usage.wall, "cpu": sw.usage.cpu,
            "total": sum(p.stat().st_size for p in files), "files": len(files),
            "page_mean": sum(pages) / max(1, len(pages)), "page_max": max(pages, default=0),
            "replays": sum(replays), "replay_pages": len(replays),
            "summary": (out / "summary.html").stat().st_size}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--week", type=int, default=5)
    parser.add_argument("--n", type=int, default=400, help="students in the class")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--rounds", type=int, default=1,
                        help="build each layout this many times, in the order ABBA... (on a busy machine)")
    args = parser.parse_args(argv)
    if args.n < 1 or args.jobs < 1 or args.n > 1000 or args.rounds < 1:
        parser.error("--n must be 1..1000, --jobs and --rounds at least 1")
    print(machine_line("none (the grading is copied, not run)"), flush=True)
    print(prepare_bytecode(), flush=True)
    with tempfile.TemporaryDirectory(prefix="simiam-pages-bench-") as tmp:
        gradings = Path(tmp) / "gradings"
        gradings.mkdir()
        began = time.monotonic()
        grade_once(args.week, gradings)
        print(f"graded the week {args.week} solution and stub once (hidden checks): "
              f"{time.monotonic() - began:.1f} s", flush=True)
        os.environ[GRADINGS] = str(gradings)
        layouts = (("self-contained (baseline)", "pages_bench:self_contained_pages"),
                   ("shared assets", "pages_bench:shared_pages"))
        rows = []
        for k in range(args.rounds):    # ABBA...: each layout as often first as second under a drifting load
            for name, fn in layouts if k % 2 == 0 else layouts[::-1]:
                row = build(args.week, args.n, args.jobs, fn, Path(tmp) / f"{k}-{name.split()[0]}")
                rows.append((k, name, row))
                shutil.rmtree(Path(tmp) / f"{k}-{name.split()[0]}")
    bases = {k: row for k, name, row in rows if name == layouts[0][0]}   # each round's own baseline
    print(f"week {args.week}, {args.n} students, --jobs {args.jobs}")
    print(f"{'layout':<26} {'total MB':>9} {'x base':>6} {'files':>6} {'page KB mean':>12} {'max':>6} "
          f"{'replays MB':>10} {'summary KB':>10} {'pages/s':>8} {'x base':>6} {'CPU s/student':>13}")
    for k, name, row in rows:
        base = bases[k]
        missing = "" if row["graded"] == args.n else f"  (only {row['graded']} written)"
        print(f"{name:<26} {row['total'] / 1e6:>9.1f} {ratio(row['total'], base['total']):>6.2f} "
              f"{row['files']:>6} {row['page_mean'] / 1e3:>12.1f} {row['page_max'] / 1e3:>6.1f} "
              f"{row['replays'] / 1e6:>10.1f} {row['summary'] / 1e3:>10.1f} "
              f"{args.n / row['seconds']:>8.1f} {ratio(base['seconds'], row['seconds']):>6.2f} "
              f"{row['cpu'] / args.n:>13.3f}{missing}")
    print("total MB: everything in the output folder (pages, replay pages, assets, results, class files); "
          "page KB: a student's report; replays MB: the replay pages (replays/); pages/s: students whose "
          "pages were written per wall second (the grading copied, so this is the pages' cost with the "
          "batch's own writing); x base: against the baseline built in the same round (its figure divided "
          "by this one's for speed, this one's divided by the baseline's for size)")
    print(load_after_line())
    return 0


if __name__ == "__main__":
    sys.exit(main())
