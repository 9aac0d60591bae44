"""Does every kept wrong version lose exactly its `# aims:` checks at other seeds than the tests' 2014?

    python benchmarks/discrimination_seeds.py [--seeds 3]

The discrimination tests (tests/grader/test_checks_fail.py) grade each wrong version in tests/data/wrong at
seed 2014 only. Property checks draw other cases at other seeds, so this grades each one at seeds
1..N and prints how many gradings lost exactly the aimed checks, and the others (missed, extra). A figure
to compare between versions of the case drawing (docs/performance.md), not a test.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# ROOT first, or tests/ (which holds a folder named grader) would shadow the grader package
sys.path[:0] = [str(ROOT), str(ROOT / "tests" / "grader"), str(ROOT / "tests")]

from mistakes import DATA, read_mistake  # noqa: E402
from wrong_submissions import build, week_of  # noqa: E402

from grader.grading import grade_submission  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, default=3, help="grade at seeds 1..N")
    args = p.parse_args(argv)
    exact = total = 0
    others = []
    with tempfile.TemporaryDirectory(prefix="simiam-discrimination-") as tmp:
        for patch in sorted((DATA / "wrong").glob("*.patch")):
            aims = set(read_mistake(patch).aims or ())
            folder = build(patch.stem, Path(tmp) / patch.stem)
            for seed in range(1, args.seeds + 1):
                result = grade_submission(week_of(patch.stem), folder, seed=seed)
                lost = {c["id"] for c in result["checks"] if c["status"] != "passed"}
                total += 1
                exact += lost == aims
                if lost != aims:
                    others.append(f"  {patch.stem} seed {seed}: missed {sorted(aims - lost)}, "
                                  f"extra {sorted(lost - aims)}")
    print(f"lost exactly the aimed checks: {exact} of {total} gradings (seeds 1..{args.seeds})")
    print("\n".join(others))
    return 0


if __name__ == "__main__":
    sys.exit(main())
