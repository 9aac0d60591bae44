"""Make (and check) the week-7 hidden set: goals in the trap world, the world turned about the start.

    python -m instructor_tools.hidden_week7   # rewrites instructor_tools/hidden/week7.json (~1 h, 2 cores)

The week-7 automaton is chaotic in the trap: whether the robot leaves a wall depends on a window of a step
or two where progress is made and the sliding test says no, so one last bit of a BLAS kernel can send the
reference round the arena wall for the rest of the minute (issue 20: 11 of the first set's 33 variants,
made at one kernel from one start, were missed by the reference or by the manual's progress rule under
another kernel or from a start moved by 1e-9 m). A variant is a fair test only where that does not happen,
so a candidate (a goal on a 0.15 m grid, the world turned by k eighths of a turn) is kept only if:

1. the reference solution (solutions/week7) and the manual's progress rule (tests/data/wrong/
   good_week7_manual_epsilon.patch, a correct alternative) both bring the TRUE position within 0.05 m of the
   goal by MAX_T of the check's 60 s, without a collision and never closer than MIN_CLEARANCE to an
   obstacle, while neither the untouched stub (straight for the goal) nor an automaton that never follows
   a wall (tests/data/wrong/week7_progress_point_max.patch: progress always made) reaches it: the variant
   needs the week's wall following (the goals straight out of the trap's opening do not, and without this
   rule they were most of the robust ones);
2. all four do so from the start moved by each of NUDGES as well, under every BLAS kernel this CPU runs
   (instructor_tools.kernels: each kernel is judged in a process of its own);
3. every other kept week-7 version (tests/data/wrong/*week7*.patch: correct alternatives and wrong ones
   alike) is *decided* on it: reaches it from every start under every kernel, or from none (issue 20: a
   verdict a kernel flips was never a verdict; on the first robust set, 7 of 22 variants were reached or
   missed by the last bits by one of week7_progress_strict, week7_wall_far_side, week7_stub_thresholds,
   week7_direction_in_inputs or week7_sigma_transposed, and the full verdict matrix saw
   week7_progress_strict's hidden check flip).

Candidates: a goal on a 0.15 m grid, the world turned by k eighths of a turn (the quarter turns of the first
set and the headings between them: few goals pass all three rules with the robot facing the trap's walls,
and the draw wants three different start quarters). Judging is done in processes of the kernel in question,
two at a time, cheapest rule first: the four runs from the declared start at the official kernel, then the
nudged starts and every kept version at the official kernel, then the other kernels.

tests/grader/test_hidden_week7.py re-checks the kept variants (at the official kernel, with the nudged
starts); tests/grader/test_verdict_margins.py grades a seed's picks under every kernel.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from grader.checks.week7 import D_GOAL, HIDDEN_SECONDS, turned
from grader.platforms.wrong_versions import apply_mistake
from grader.scenarios import min_clearance
from instructor_tools import kernels
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "instructor_tools" / "hidden" / "week7.json"
ALTERNATIVE = ROOT / "tests" / "data" / "wrong" / "good_week7_manual_epsilon.patch"
NO_FOLLOW = ROOT / "tests" / "data" / "wrong" / "week7_progress_point_max.patch"
KEPT = ROOT / "tests" / "data" / "wrong"
MAX_T = 50.0          # s of the 60: arrival with 10 s to spare
MIN_CLEARANCE = 0.005  # m, at every step
# m: the last bits a kernel changes, and a thousand times more (the automaton is chaotic: a variant the
# reference reaches from every start within 1e-6 m can still be missed from one 1e-4 m away; the check
# needs a margin over the last bits, and those variants are the ones that need the wall following)
NUDGES = ((1e-9, 1e-9), (-1e-9, -1e-9), (1e-6, -1e-6), (-1e-6, 1e-6))
GRID = [round(-1.2 + 0.15 * k, 2) for k in range(17)]  # goal coordinates, m
OF = 8
NEAR = 0.2  # m: goals this close to an obstacle are not candidates


def outcome(folder: Path, variant: dict, nudge: tuple[float, float] = (0.0, 0.0)) -> dict:
    """How `folder`'s code does on one variant, the check's way (the TRUE position within D_GOAL of the goal
    in HIDDEN_SECONDS, stopped at a collision), from the start moved by `nudge`: {"reached", "t",
    "clearance"} (t the arrival or the end, clearance 0 after a collision)."""
    week = get_week(7)
    world, goal = turned(load_world(week.world), tuple(variant["goal"]), variant["turn"], variant["of"])
    sub = load_submission(folder, week)
    if not sub.ok:
        raise RuntimeError(f"{folder} does not load: {sub.errors[0]}")
    brain = LocalBrain(sub, week, week.settings.with_changes(goal=goal).as_dict())
    sim = Simulator(world, brain, week.spec, dt=week.dt, start=(nudge[0], nudge[1], 0.0))
    trace = sim.run(HIDDEN_SECONDS, until=lambda rec: math.dist(rec.pose[:2], goal) < D_GOAL)
    assert trace.ending is not None
    reached = trace.collision is None and trace.ending.reason.name == "UNTIL"
    gap = 0.0 if trace.collision is not None else min_clearance(trace, world, week.spec)
    return {"reached": reached, "t": round(trace.ending.t, 6), "clearance": gap}


def with_margin(seen: dict) -> bool:
    return seen["reached"] and seen["t"] <= MAX_T and (seen["clearance"] or 0.0) >= MIN_CLEARANCE


def candidates() -> list[dict]:
    """Goals on the grid, not within NEAR of an obstacle of the (unturned) world, for every turn."""
    from grader.laps import distance_to

    world = load_world(get_week(7).world)
    out = []
    for x in GRID:
        for y in GRID:
            if math.hypot(x, y) < 0.5 or distance_to((x, y), world.obstacles) < NEAR:
                continue
            if any(_inside((x, y), poly) for poly in world.obstacles):
                continue
            out += [{"goal": [x, y], "turn": turn, "of": OF} for turn in range(OF)]
    return out


def _inside(point: tuple[float, float], poly) -> bool:
    xs, ys = [p[0] for p in poly], [p[1] for p in poly]
    return min(xs) <= point[0] <= max(xs) and min(ys) <= point[1] <= max(ys)  # the obstacles are boxes


def folders(into: Path) -> dict[str, Path]:
    """The reference and the correct alternative (they must reach the goals), the stub and the automaton
    that never follows a wall (they must not)."""
    alternative = apply_mistake(ALTERNATIVE, ROOT / "solutions", into / "alternative")[1]
    no_follow = apply_mistake(NO_FOLLOW, ROOT / "solutions", into / "no_follow")[1]
    return {"reference": ROOT / "solutions" / "week7", "alternative": alternative,
            "stub": ROOT / "assignments" / "week7", "no_follow": no_follow}


def kept_versions(into: Path) -> dict[str, Path]:
    """Every other kept week-7 version (rule 3): each must be decided on a variant."""
    rules = {ALTERNATIVE.stem, NO_FOLLOW.stem}
    return {patch.stem: apply_mistake(patch, ROOT / "solutions", into / patch.stem)[1]
            for patch in sorted(KEPT.glob("*week7*.patch")) if patch.stem not in rules}


REACH = ("reference", "alternative")
MISS = ("stub", "no_follow")


def fair(found: dict[str, Path], variant: dict, nudge: tuple[float, float] = (0.0, 0.0)) -> bool:
    """The reference and the alternative reach the variant with the margins, the stub and the automaton
    without wall following do not, from the start moved by `nudge`."""
    return (all(with_margin(outcome(found[who], variant, nudge)) for who in REACH)
            and not any(outcome(found[who], variant, nudge)["reached"] for who in MISS))


def decided(kept: dict[str, Path], variant: dict, nudges) -> dict[str, bool] | None:
    """{kept version: whether it reaches the variant} when that is the same from every start, else None."""
    seen = {}
    for name, folder in kept.items():
        got = {outcome(folder, variant, nudge)["reached"] for nudge in nudges}
        if len(got) > 1:
            return None
        seen[name] = got.pop()
    return seen


def judge(variants: list[dict], full: bool) -> list[dict]:
    """In this process's kernel, per variant: {"fair": rules 1-2 from every start, "decided": rule 3's
    outcomes or None}; with `full` False only rule 1 from the declared start (the cheap first pass)."""
    starts = ((0.0, 0.0), *NUDGES) if full else ((0.0, 0.0),)
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        found = folders(Path(tmp))
        kept = kept_versions(Path(tmp) / "kept") if full else {}
        for v in variants:
            ok = all(fair(found, v, n) for n in starts)
            out.append({"fair": ok, "decided": decided(kept, v, starts) if ok and full else None})
    return out


def judged_under(kernel: str, variants: list[dict], full: bool) -> list[dict]:
    """judge() in processes whose BLAS kernel is `kernel`, the variants split between two of them."""
    halves = [variants[0::2], variants[1::2]]

    def one(part: list[dict]) -> list[dict]:
        done = subprocess.run([sys.executable, "-m", "instructor_tools.hidden_week7", "--judge",
                               "full" if full else "first"], input=json.dumps(part),
                              env=kernels.environment(kernel), capture_output=True, text=True, check=True,
                              cwd=ROOT)
        return json.loads(done.stdout)

    with ThreadPoolExecutor(max_workers=2) as pool:
        even, odd = pool.map(one, halves)
    return [even[k // 2] if k % 2 == 0 else odd[k // 2] for k in range(len(variants))]


def main() -> int:
    if sys.argv[1:2] == ["--judge"]:
        print(json.dumps(judge(json.loads(sys.stdin.read()), sys.argv[2:] == ["full"])))
        return 0
    official, *others = kernels.runnable()
    pool = candidates()
    seen = judged_under(official, pool, full=False)
    first = [v for v, s in zip(pool, seen, strict=True) if s["fair"]]
    print(f"{len(first)} of {len(pool)} candidates pass at the official kernel from the declared start",
          flush=True)
    seen = judged_under(official, first, full=True)
    kept = [(v, s["decided"]) for v, s in zip(first, seen, strict=True)
            if s["fair"] and s["decided"] is not None]
    print(f"{len(kept)} of them from every nudged start, every kept version decided", flush=True)
    for kernel in others:
        seen = judged_under(kernel, [v for v, _ in kept], full=True)
        kept = [(v, d) for (v, d), s in zip(kept, seen, strict=True) if s["fair"] and s["decided"] == d]
        print(f"{len(kept)} of them under {kernel} too", flush=True)
    names = [official, *others]
    with tempfile.TemporaryDirectory() as tmp:
        found = folders(Path(tmp))
        kept = [{**v, "reference_seconds": outcome(found["reference"], v)["t"]} for v, _ in kept]
    data = {
        "about": (
            "Week-7 hidden variants: a goal in the final world (the trap around the start) and the world "
            "with the goal turned about the start by 2*pi*turn/of rad, so the robot starts facing another "
            "way. Made by python -m instructor_tools.hidden_week7: the reference solution (the course "
            "author's automaton) and the same with the manual's progress rule (epsilon = 0.1) both bring the "
            f"TRUE position within 0.05 m of the goal by {MAX_T:g} s of the 60 s at dt 0.05, never closer "
            f"than {MIN_CLEARANCE} m to an obstacle, from the declared start and from starts moved by up to "
            f"1e-6 m, under every BLAS kernel ({', '.join(names)}); neither the untouched stub (go straight "
            "to the goal, stop there) nor the automaton that never follows a wall (progress always made) "
            "reaches it, there too; every other kept week-7 version (tests/data/wrong) reaches it from every "
            "start under every kernel, or from none. reference_seconds is when the reference got there from "
            "the declared start at the official kernel. tests/grader/test_hidden_week7.py re-checks the "
            "reference on every variant. A grading seed picks 3."
        ),
        "variants": kept,
    }
    OUT.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    print(f"{len(kept)} variants written to {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
