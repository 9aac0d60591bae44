"""Verdicts under one numeric configuration: the solutions, the stubs and the kept versions graded in a
process of its own, whose BLAS kernel (simiam.numerics, SIMIAM_BLAS_KERNEL) is chosen before numpy loads
there and in its sandbox workers, and whose scenario runs start nudged (grade_submission's start_nudge).

    python tests/grader/verdict_matrix.py --kernel Nehalem --nudge=-1e-9 [--only LABEL[::CHECK] ...]

prints one JSON object: {"numerics": what the workers loaded, "seconds": wall time, "verdicts": {label:
{check id: [status, points]}}}. A label is `solutions/weekN`, `assignments/weekN` (the stub) or the name of
a kept version in tests/data/wrong; LABEL::CHECK grades that check only. tests/grader/test_verdict_margins.py
compares these objects across kernels and nudged starts.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
TESTS = HERE.parent
ROOT = TESTS.parent
SEED = 2014
SNAPSHOT = TESTS / "data" / "verdicts" / "seed2014.json"  # official grading's verdicts (test_checks_fail)


def versions() -> dict[str, int]:
    """{label: week} of everything whose verdicts must not hang on the last bit: each week's solution, its
    stub and every kept version in tests/data/wrong."""
    from mistakes import DATA, read_mistake

    out: dict[str, int] = {}
    weeks = sorted(int(p.name.removeprefix("week")) for p in (ROOT / "solutions").glob("week*"))
    for week in weeks:
        out[f"solutions/week{week}"] = out[f"assignments/week{week}"] = week
    for patch in sorted((DATA / "wrong").glob("*.patch")):
        out[patch.stem] = read_mistake(patch).week
    return out


def grade_here(wanted: list[str], nudge: float, seed: int = SEED) -> dict:
    """Grade each `label` or `label::check` of `wanted` (hidden checks included) in this process, whose kernel
    is the one simiam pinned when it was imported, with every scenario run's start moved by (nudge, nudge)."""
    from mistakes import build

    from grader.grading import grade_submission

    weeks = versions()
    verdicts: dict[str, dict[str, list]] = {}
    numerics: dict = {}
    began = time.monotonic()
    built: dict[str, Path] = {}  # a label asked for with two checks is built once
    with tempfile.TemporaryDirectory(prefix="simiam-verdicts-") as tmp:
        for item in wanted:
            label, _, check = item.partition("::")
            week = weeks[label]
            if label not in built:
                built[label] = ROOT / label if "/" in label else build("wrong", label, Path(tmp), week)
            folder = built[label]
            result = grade_submission(week, folder, seed=seed, hidden=True, only=check or None,
                                      start_nudge=(nudge, nudge))
            numerics = result.get("numerics") or numerics
            for c in result["checks"]:
                verdicts.setdefault(label, {})[c["id"]] = [c["status"], round(c["points"], 9)]
    return {"numerics": numerics, "seconds": round(time.monotonic() - began, 1), "verdicts": verdicts}


def grade_in_process(kernel: str, nudge: float, wanted: list[str], seed: int = SEED) -> dict:
    """grade_here in a fresh process whose BLAS kernel is `kernel` (a core name or "native")."""
    from instructor_tools.kernels import environment

    command = [sys.executable, str(Path(__file__)), "--kernel", kernel, f"--nudge={nudge!r}",
               "--seed", str(seed), "--only", *wanted]
    done = subprocess.run(command, env=environment(kernel), capture_output=True, text=True, cwd=ROOT)
    if done.returncode != 0:
        raise RuntimeError(f"grading under {kernel} (nudge {nudge}) failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--kernel", required=True)
    parser.add_argument("--nudge", type=float, default=0.0)
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--only", nargs="*")
    parser.add_argument("--snapshot", action="store_true",
                        help=f"rewrite {SNAPSHOT.relative_to(ROOT)} (every version, seed {SEED}, its kernel)")
    args = parser.parse_args()
    os.environ["SIMIAM_BLAS_KERNEL"] = args.kernel  # before simiam, and so numpy, loads below
    sys.path[:0] = [str(ROOT), str(TESTS)]
    import simiam  # noqa: F401  (pins the kernel)

    graded = grade_here(args.only or list(versions()), args.nudge, args.seed)
    if args.snapshot:
        if args.only or args.nudge or args.seed != SEED:
            parser.error("--snapshot grades every version from the declared start at the default seed")
        old = json.loads(SNAPSHOT.read_text())
        new = {**old, "numerics": graded["numerics"], "verdicts": graded["verdicts"]}
        SNAPSHOT.write_text(json.dumps(new, indent=1) + "\n")
    print(json.dumps(graded))


if __name__ == "__main__":
    main()
