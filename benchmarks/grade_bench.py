"""Seconds to grade one submission per week (the reference solutions), visible checks and with --hidden.

    python benchmarks/grade_bench.py [--repeat 3] [--sandbox auto|bwrap|subprocess]

Prints one line per week: best and median wall seconds over the repetitions, the checks' own time, and
the isolation used. A figure to read, not a test (the target is <= 2 s wall for week 3).
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

from grader.grading import grade_submission

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--sandbox", default="auto")
    args = p.parse_args()
    for hidden in (False, True):
        for week in (1, 2, 3, 4):
            walls, checks, isolation = [], [], "?"
            for _ in range(args.repeat):
                began = time.perf_counter()
                result = grade_submission(week, ROOT / "solutions" / f"week{week}", seed=2014, hidden=hidden,
                                          sandbox=args.sandbox)
                walls.append(time.perf_counter() - began)
                checks.append(sum(result["timing"]["checks"].values()))
                isolation = result.get("isolation", "?")
            print(f"week{week} {'hidden ' if hidden else 'visible'}: wall best {min(walls):.2f} s, "
                  f"median {statistics.median(walls):.2f} s; checks {statistics.median(checks):.2f} s; "
                  f"{len(result['checks'])} checks, score {result['score']:g}/{result['max_score']:g}, "
                  f"isolation {isolation}")


if __name__ == "__main__":
    main()
