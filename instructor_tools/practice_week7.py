"""Make the week-7 practice set: variants drawn as the hidden ones are, vetted by their rules, never one.

    python -m instructor_tools.practice_week7   # rewrites grader/practice/week7.json (about an hour, 2 cores)

The hidden set (instructor_tools/hidden_week7.py) keeps every goal of a 0.15 m grid, in the world turned by
k eighths of a turn, that passes its three rules; every other candidate of that grid failed one. So the
practice candidates lie on the same grid shifted by half a step (0.075 m): never a hidden goal, drawn from
the same box with the same exclusions. They are tried in an order of their own (random.Random(STREAM)),
each judged by hidden_week7's own rules (hidden_week7.judge: the reference and the manual's progress rule
reach it with the margins, the stub and the automaton that never follows a wall do not, from every nudged
start; every kept week-7 version decided) under every BLAS kernel, until COUNT are kept; over the first
SPREAD_FOR candidates a start quarter already kept waits. Judging a candidate under every kernel takes
minutes and most fail, so the set is small (docs/design.md, "Practice sets", says what a run cost);
tests/grader/test_practice.py checks that none equals a hidden variant. Each kept variant is written at
once; --skip N --resume JSON continue an interrupted run.
"""

from __future__ import annotations

import json
import math
import random
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from grader.hidden import load_hidden
from grader.hidden.draw import turn_quarter
from grader.practice import PRACTICE_DIR
from instructor_tools import hidden_week7, kernels
from simiam.course.weeks import get_week
from simiam.world import load_world

OUT = PRACTICE_DIR / "week7.json"
STREAM = "practice:week7"
COUNT = 4
SPREAD_FOR = 120
GRID = [round(-1.125 + 0.15 * k, 3) for k in range(16)]  # half-way between hidden_week7.GRID's goals


def candidates() -> list[dict]:
    """Goals on the shifted grid, with hidden_week7's exclusions, for every turn; in STREAM's order."""
    from grader.laps import distance_to

    world = load_world(get_week(7).world)
    out = []
    for x in GRID:
        for y in GRID:
            if math.hypot(x, y) < 0.5 or distance_to((x, y), world.obstacles) < hidden_week7.NEAR:
                continue
            if any(hidden_week7._inside((x, y), poly) for poly in world.obstacles):
                continue
            out += [{"goal": [x, y], "turn": turn, "of": hidden_week7.OF} for turn in range(hidden_week7.OF)]
    hidden = load_hidden(7)
    secret = {_key(v) for v in (hidden or {}).get("variants", [])}
    out = [v for v in out if _key(v) not in secret]
    random.Random(STREAM).shuffle(out)
    return out


def _key(v: dict) -> tuple:
    return (round(v["goal"][0], 6), round(v["goal"][1], 6), v["turn"] * 360 // v["of"])


def _judge(kernel: str, variants: list[dict], full: bool) -> list[dict]:
    """hidden_week7.judge in a process whose BLAS kernel is `kernel`."""
    done = subprocess.run([sys.executable, "-m", "instructor_tools.hidden_week7", "--judge",
                           "full" if full else "first"], input=json.dumps(variants),
                          env=kernels.environment(kernel), capture_output=True, text=True, check=True,
                          cwd=hidden_week7.ROOT)
    return json.loads(done.stdout)


def kept_everywhere(variant: dict, official: str, others: list[str]) -> bool:
    """Rules 1-3 at the official kernel, then the same outcomes under every other kernel (two at a time)."""
    first = _judge(official, [variant], full=True)[0]
    if not first["fair"] or first["decided"] is None:
        return False
    with ThreadPoolExecutor(max_workers=2) as pool:
        seen = list(pool.map(lambda k: _judge(k, [variant], full=True)[0], others))
    return all(s["fair"] and s["decided"] == first["decided"] for s in seen)


def main(argv: list[str] | None = None) -> int:
    import argparse

    parser = argparse.ArgumentParser(prog="python -m instructor_tools.practice_week7")
    parser.add_argument("--resume", default="[]", metavar="JSON",
                        help="variants an interrupted run kept (its log prints them), judged again never")
    parser.add_argument("--skip", type=int, default=0, metavar="N",
                        help="the candidates an interrupted run had judged: start after them")
    args = parser.parse_args(argv)
    official, *others = kernels.runnable()
    pool = candidates()
    kept: list[dict] = json.loads(args.resume)
    quarters = {turn_quarter(v["turn"], v["of"]) for v in kept}
    if kept:
        write(kept, [official, *others])
    tried = args.skip
    batch = 24
    for start in range(args.skip, len(pool), batch):
        if len(kept) >= COUNT:
            break
        part = pool[start:start + batch]
        halves = [part[0::2], part[1::2]]
        with ThreadPoolExecutor(max_workers=2) as workers:
            even, odd = workers.map(lambda h: _judge(official, h, full=False), halves)
        first = [even[k // 2] if k % 2 == 0 else odd[k // 2] for k in range(len(part))]
        for v, seen in zip(part, first, strict=True):
            tried += 1
            quarter = turn_quarter(v["turn"], v["of"])
            # while fewer quarters than wanted are kept, a kept quarter waits (the hidden draw's spread);
            # past SPREAD_FOR candidates any quarter will do (the hidden set's 43 face three quarters, one
            # of them twice only: waiting for a rare quarter would cost hours)
            want_new = len(quarters) < min(COUNT, 4) and start < SPREAD_FOR
            if not seen["fair"] or len(kept) >= COUNT or (want_new and quarter in quarters):
                continue
            ok = kept_everywhere(v, official, others)
            print(f"{v}: {'kept' if ok else 'dropped'} ({tried} tried)", flush=True)
            if ok:
                kept.append(v)
                quarters.add(quarter)
                write(kept, [official, *others])  # each time: an interrupted run loses nothing kept
    if len(kept) < COUNT:
        print(f"only {len(kept)} of {COUNT} variants kept from {tried} candidates", flush=True)
    return 0


def write(kept: list[dict], names: list[str]) -> None:
    """Write OUT: the kept variants, each with the reference's arrival from the declared start."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        found = hidden_week7.folders(Path(tmp))
        kept = [{**v, "reference_seconds": hidden_week7.outcome(found["reference"], v)["t"]} for v in kept]
    data = {
        "about": (
            "Week-7 practice variants (not graded): a goal in the final world and the world with the goal "
            "turned about the start by 2*pi*turn/of rad. Drawn as the hidden variants are, on the hidden "
            "grid shifted by half a step (so never a hidden goal), and kept by the hidden set's own rules "
            f"(python -m instructor_tools.practice_week7): the reference solution and the manual's progress "
            f"rule reach the goal by {hidden_week7.MAX_T:g} s of the 60 s, never closer than "
            f"{hidden_week7.MIN_CLEARANCE} m to an obstacle, from starts moved by up to 1e-6 m, under every "
            f"BLAS kernel ({', '.join(names)}); the stub and an automaton that never follows a wall do not; "
            "every kept week-7 version is decided on it. Official grading runs 3 other variants, from the "
            "instructor's hidden set."
        ),
        "variants": kept,
    }
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    print(f"{len(kept)} variants written to {OUT}", flush=True)


if __name__ == "__main__":
    raise SystemExit(main())
