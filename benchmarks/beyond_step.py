"""What a warm grading of weeks 4-7 costs the GRADING process beyond the simulator's step (issue 24): the
report (its plots, its replays, its JSON), the scenario metrics (min_clearance, the laps' distances), the
traces' JSON, and in all. Optionally A/B against another checkout, alternating runs.

    python benchmarks/beyond_step.py [--weeks 4 5 6 7] [--repeat 3] [--hidden]
    python benchmarks/beyond_step.py --against /tmp/base [--rounds 3] [--weeks ...] [--hidden]

Each figure is CPU milliseconds of the grading thread (`time.thread_time`), the median of `repeat` warm
gradings of the week's solutions (seed 2014) after one to warm up; the worker's CPU is not counted (it is
not what this measures). Timers wrap functions from outside, by name, so the same script measures an older
checkout (`--against DIR` runs it there with PYTHONPATH=DIR, alternating with this tree, `rounds` times
each, and prints both medians and their ratio). Nested timers overlap: the indented rows are part of the
row above them. A figure to read, not a test: compare the two columns of one run, not runs on other days.
"""

from __future__ import annotations

import argparse
import collections
import functools
import importlib
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# (row label, dotted name of the function timed); "  " marks a part of the row above
COMPONENTS = [
    ("scenario metric: min_clearance", "grader.scenarios.min_clearance"),
    ("laps: median distance to the obstacle", "grader.laps.median_distance"),
    ("report: JSON and HTML (write_outputs)", "grader.grading.write_outputs"),
    ("  replays embedded (render_replay)", "simiam.viewer.replay.render_replay"),
    ("    of which packing the trace (pack_trace)", "simiam.viewer.replay.pack_trace"),
    ("  line charts (Chart.render)", "grader.report.svg.Chart.render"),
    ("  top views (trajectory_svg)", "grader.report.svg.trajectory_svg"),
    ("  states timelines (states_svg)", "grader.report.signal_plots.states_svg"),
]
TOTAL = "grading process in all (grade_submission)"


def _resolve(dotted: str) -> tuple[object, str] | None:
    """(owner, attribute) of a dotted function name, or None where this checkout lacks it."""
    parts = dotted.split(".")
    for cut in range(len(parts) - 1, 0, -1):
        try:
            owner: object = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        try:
            for name in parts[cut:-1]:
                owner = getattr(owner, name)
            getattr(owner, parts[-1])
        except AttributeError:
            return None
        return owner, parts[-1]
    return None


def instrument(spent: dict[str, float]) -> list[str]:
    """Wrap every component (and its `from x import f` aliases) to add its thread CPU to `spent`; the
    labels of the components this checkout lacks."""
    missing = []
    for label, dotted in COMPONENTS:
        found = _resolve(dotted)
        if found is None:
            missing.append(label)
            continue
        owner, name = found
        original = getattr(owner, name)

        def timed(*args, _fn=original, _label=label, **kwargs):
            c0 = time.thread_time()
            try:
                return _fn(*args, **kwargs)
            finally:
                spent[_label] += time.thread_time() - c0

        functools.update_wrapper(timed, original)
        setattr(owner, name, timed)
        for module in list(sys.modules.values()):
            for attr, value in list(getattr(module, "__dict__", {}).items()):
                if value is original:
                    setattr(module, attr, timed)
    return missing


def measure(weeks: list[int], repeat: int, hidden: bool) -> dict:
    """{"W" or "Wh": {label: median ms}} for this process's checkout."""
    import grader.grading as grading  # (it imports simiam first, which pins the BLAS kernel)
    from grader.checks import checks_for_week

    for week in weeks:
        checks_for_week(week)  # imported first, so that their aliases of the timed functions get wrapped
    import grader.report.html  # noqa: F401
    import simiam.viewer.replay  # noqa: F401

    spent: dict[str, float] = collections.defaultdict(float)
    missing = instrument(spent)
    figures: dict[str, dict] = {}
    for week in weeks:
        for variant in ([False, True] if hidden else [False]):
            rows: dict[str, list[float]] = collections.defaultdict(list)
            with tempfile.TemporaryDirectory(prefix="simiam-beyond-") as out:
                for k in range(repeat + 1):
                    spent.clear()
                    c0 = time.thread_time()
                    grading.grade_submission(week, ROOT / "solutions" / f"week{week}", seed=2014,
                                             hidden=variant, out_dir=Path(out))
                    total = time.thread_time() - c0
                    if k == 0:
                        continue  # the warm-up: lazy imports and caches
                    rows[TOTAL].append(total * 1000)
                    for label, _ in COMPONENTS:
                        if label not in missing:
                            rows[label].append(spent[label] * 1000)
            figures[f"{week}{'h' if variant else ''}"] = {k: statistics.median(v) for k, v in rows.items()}
    return figures


def _key_text(key: str) -> str:
    return f"week {key.rstrip('h')}" + (" with --hidden" if key.endswith("h") else "")


def print_one(figures: dict) -> None:
    for key, rows in figures.items():
        print(f"{_key_text(key)}: grading-process CPU ms, median of the warm gradings, and the share of "
              f"the same run's grading process in all")
        total = rows[TOTAL]
        for label in [TOTAL] + [c[0] for c in COMPONENTS]:
            value = rows.get(label)
            share = "" if value is None or label == TOTAL else f" {value / total:6.1%}"
            print(f"  {label:48s} {'n/a' if value is None else f'{value:8.1f}'}{share}")


def print_ab(base: list[dict], ours: list[dict], base_dir: str) -> None:
    print(f"A = {base_dir}, B = {ROOT}; medians over the rounds of each round's medians, grading-process "
          f"CPU ms; B/A")
    for key in ours[0]:
        print(f"{_key_text(key)}:")
        for label in [TOTAL] + [c[0] for c in COMPONENTS]:
            a = [r[key][label] for r in base if label in r[key]]
            b = [r[key][label] for r in ours if label in r[key]]
            if not a or not b:
                print(f"  {label:48s} {'n/a':>8s}")
                continue
            ma, mb = statistics.median(a), statistics.median(b)
            spread = f"A {min(a):.1f}-{max(a):.1f}, B {min(b):.1f}-{max(b):.1f}"
            rel = f"{mb / ma:5.2f}" if ma > 0.05 else "  -  "
            print(f"  {label:48s} A {ma:8.1f}  B {mb:8.1f}  {rel}   ({spread})")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--weeks", type=int, nargs="+", default=[4, 5, 6, 7])
    p.add_argument("--repeat", type=int, default=3, help="warm gradings per figure (the median is printed)")
    p.add_argument("--hidden", action="store_true", help="also grade with the hidden checks")
    p.add_argument("--against", metavar="DIR", help="another checkout to alternate with (A/B)")
    p.add_argument("--rounds", type=int, default=3, help="with --against: runs of each checkout")
    p.add_argument("--json", action="store_true", help=argparse.SUPPRESS)  # one run's figures, for --against
    args = p.parse_args(argv)
    if args.json:
        print(json.dumps(measure(args.weeks, args.repeat, args.hidden)))
        return 0
    from simiam.machine import load_after_line, machine_line, prepare_bytecode

    print(machine_line("bubblewrap if available (grade's default)"), flush=True)
    print(prepare_bytecode(), flush=True)
    if not args.against:
        print_one(measure(args.weeks, args.repeat, args.hidden))
        print(load_after_line())
        return 0
    base_dir = str(Path(args.against).resolve())
    command = [sys.executable, str(Path(__file__).resolve()), "--json", "--repeat", str(args.repeat),
               "--weeks", *map(str, args.weeks), *(["--hidden"] if args.hidden else [])]
    runs: dict[str, list[dict]] = {"A": [], "B": []}
    for _ in range(args.rounds):
        for side, path in (("A", base_dir), ("B", str(ROOT))):  # alternating: the load hits both alike
            env = {**os.environ, "PYTHONPATH": path}
            done = subprocess.run(command, env=env, capture_output=True, text=True, cwd=path)
            if done.returncode != 0:
                print(f"{side} ({path}) failed: {done.stderr[-2000:]}", file=sys.stderr)
                return 2
            runs[side].append(json.loads(done.stdout.strip().splitlines()[-1]))
            print(f"  round {len(runs[side])} {side} done; {load_after_line()}", flush=True)
    print_ab(runs["A"], runs["B"], base_dir)
    print(load_after_line())
    return 0


if __name__ == "__main__":
    sys.exit(main())
