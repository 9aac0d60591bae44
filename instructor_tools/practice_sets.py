"""Make the practice sets of weeks 3-6: hidden-like variants, vetted with the hidden ones' margins, never one.

    python -m instructor_tools.practice_sets 3 4 5 6   # rewrites grader/practice/week{3,4,5,6}.json (minutes)
    python -m instructor_tools.practice_week7          # week 7, whose vetting takes longer

Each week's candidates come from the generator its hidden variants come from, on values the hidden set never
holds, in a random stream of their own (random.Random("practice:weekN")); each is kept only when the
reference solution passes it with the margin the hidden variants were vetted with; then as many as COUNT
say are drawn spread over the draw's kinds (grader.hidden.draw, as a grading seed draws the hidden ones).

- week 3: goals drawn as grader.checks.week3 draws them per seed (the same box, distances and turns), but
  on the 0.01 m grid shifted by 0.005 m, and start headings off the 0.01 rad grid: no seed can ever draw a
  practice variant (every seed's draw is rounded to the 0.01 grid), and no seed's draw changes. Kept when
  the reference and the alternative with other gains reach the goal with tests/grader/test_week3_starts.py's
  time and clearance to spare; a tracking goal when both settle and overshoot with
  instructor_tools/tracking_week3.py's margins.
- week 4: the world mirrored and turned, by odd 48ths of a turn (the hidden set turns by 24ths, so halfway
  between its headings); kept when the reference drives the hidden set's 60 s with no collision, and never
  closer than MIN_CLEARANCE_WEEK4 to an obstacle.
- week 5: starts and goals drawn by the hidden set's rules (0.2 m and 0.25 m from every obstacle, 1 m
  apart, on the 0.01 grid), from another random stream, none equal to a hidden one; kept by the hidden
  set's rules (the reference reaches the goal in at most 45 s, never closer than 0.03 m, at most 1.5
  switches per second).
- week 6: start headings (k + 1/2) * pi/6, halfway between the hidden set's k * pi/6, either side, the same
  d_fw values; kept by instructor_tools/hidden_week6.py's own margins.

tests/grader/test_practice.py checks that no practice variant equals a hidden one (for week 3: that no seed
can draw one).
"""

from __future__ import annotations

import json
import math
import random
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from grader.hidden import load_hidden
from grader.hidden.draw import draw, heading_quarter, turn_quarter
from grader.practice import PRACTICE_DIR
from grader.scenarios import min_clearance
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import World, load_world

ROOT = Path(__file__).resolve().parents[1]
WRONG = ROOT / "tests" / "data" / "wrong"
COUNT = {3: 6, 4: 6, 5: 6, 6: 6}
MIN_CLEARANCE_WEEK4 = 0.01  # m: the hidden set asked only for no collision; a practice verdict gets a margin


def _write(week: int, about: str, variants: list[dict[str, Any]]) -> None:
    out = PRACTICE_DIR / f"week{week}.json"
    out.write_text(json.dumps({"about": about, "variants": variants}, indent=1) + "\n", encoding="utf-8")
    print(f"{len(variants)} practice variants written to {out}", flush=True)


def _folder(name: str, into: Path) -> Path:
    """solutions/weekN, or a kept correct alternative applied to solutions/ in `into`."""
    from grader.platforms.wrong_versions import apply_mistake

    return apply_mistake(WRONG / f"{name}.patch", ROOT / "solutions", into / name)[1]


# ------------------------------------------------------------------------------------------------ week 3
def _off_grid(rng: random.Random, low: float, high: float) -> float:
    """A value in [low, high] on the 0.01 grid shifted by 0.005: round(x, 2) never gives one."""
    return round(round(rng.uniform(low, high - 0.01), 2) + 0.005, 3)


def week3() -> None:
    from grader.checks.week3 import ROBOT_D_STOP, TRACKING_TURN, drawable, drawable_from
    from instructor_tools.tracking_week3 import tracking, with_margin

    arrival_spare, clearance_spare = 10.0, 0.1  # tests/grader/test_week3_starts.py
    week = get_week(3)
    world = load_world(week.world)

    def reaches(folder: Path, goal: tuple[float, float], start: tuple[float, float, float]) -> bool:
        sub = load_submission(folder, week)
        settings = week.settings.with_changes(goal=list(goal), d_stop=ROBOT_D_STOP, state="go_to_goal")
        brain = LocalBrain(sub, week, settings.as_dict(), start=start)
        sim = Simulator(World(world.name, world.obstacles, [start], goal, world.source), brain, week.spec,
                        dt=week.dt, start=start)
        trace = sim.run(week.seconds, until=lambda rec: math.dist(rec.pose[:2], goal) < week.settings.d_stop)
        assert trace.ending is not None
        arrived = trace.ending.t if trace.ending.reason.name == "UNTIL" else None
        gap = min_clearance(trace, world, week.spec)
        return (arrived is not None and arrived <= week.seconds - arrival_spare and gap is not None
                and gap >= clearance_spare)

    rng = random.Random("practice:week3")
    variants: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory() as tmp:
        folders = (ROOT / "solutions" / "week3", _folder("good_week3_other_gains", Path(tmp)))
        origin = (0.0, 0.0, 0.0)
        while sum(1 for v in variants if v["check"] == "other_goals" and "start" not in v) < 4:
            goal = (_off_grid(rng, -1.1, 1.1), _off_grid(rng, -1.1, 1.1))
            if drawable(goal, (0.35, math.pi)) and all(reaches(f, goal, origin) for f in folders):
                variants.append({"check": "other_goals", "goal": list(goal)})
        while sum(1 for v in variants if "start" in v) < 2:
            start = (_off_grid(rng, -0.6, 0.6), _off_grid(rng, -0.6, 0.6), _off_grid(rng, -math.pi, math.pi))
            goal = (_off_grid(rng, -1.1, 1.1), _off_grid(rng, -1.1, 1.1))
            if drawable_from(start, goal) and all(reaches(f, goal, start) for f in folders):
                variants.append({"check": "other_goals", "goal": list(goal), "start": list(start)})
        while sum(1 for v in variants if v["check"] == "tracking_other_goal") < 2:
            goal = (_off_grid(rng, -1.1, 1.1), _off_grid(rng, -1.1, 1.1))
            if drawable(goal, TRACKING_TURN) and all(with_margin(tracking(f, goal)) for f in folders):
                variants.append({"check": "tracking_other_goal", "goal": list(goal)})
    _write(3, (
        "Week-3 practice variants (not graded): goals (and two starts away from the origin) drawn by the "
        "rules official grading draws its goals by, but on the 0.01 m grid shifted by 0.005 m, so no grading "
        "seed ever draws one. Made by python -m instructor_tools.practice_sets 3: the reference solution and "
        "a correct alternative with other gains reach each goal with 10 s and 0.1 m to spare; for the "
        "tracking goals both settle within 2 s and overshoot at most 7 %. Official grading runs other goals, "
        "drawn per seed."), variants)


# ------------------------------------------------------------------------------------------------ week 4
def week4() -> None:
    from grader.checks.week4 import _variant

    week = get_week(4)
    solution = load_submission(ROOT / "solutions" / "week4", week)
    hidden = {(v["turn"] * 48 // v["of"], v["mirror"]) for v in load_hidden(4)["variants"]}
    kept = []
    for turn in range(1, 48, 2):  # odd 48ths: between the hidden set's 24ths
        for mirror in (False, True):
            if (turn, mirror) in hidden:
                continue
            world = _variant(load_world("week4"), turn, 48, mirror)
            trace = Simulator(world, LocalBrain(solution, week, week.settings.as_dict()), week.spec,
                              dt=week.dt).run(60.0)
            gap = 0.0 if trace.collision is not None else min_clearance(trace, world, week.spec)
            ok = gap is not None and gap >= MIN_CLEARANCE_WEEK4
            print(f"week 4 {world.name}: {'kept' if ok else 'dropped'} (clearance {gap})", flush=True)
            if ok:
                kept.append({"turn": turn, "of": 48, "mirror": mirror})
    picks = draw(kept, COUNT[4], "practice:week4", lambda v: (turn_quarter(v["turn"], v["of"]), v["mirror"]))
    _write(4, (
        "Week-4 practice variants (not graded): the week-4 world mirrored in y (when `mirror`) and "
        "turned about the start by 2*pi*turn/of rad, halfway between the headings of official "
        "grading's hidden variants. Made by python -m instructor_tools.practice_sets 4: the "
        "reference solution drove 60 s at v = 0.15 without a collision, never closer than "
        f"{MIN_CLEARANCE_WEEK4} m to an obstacle, in each; the check runs 30 s. Official grading runs "
        "3 other variants, from the instructor's hidden set."), picks)


# ------------------------------------------------------------------------------------------------ week 5
def week5() -> None:
    from grader.checks.week5 import D_STOP, setup
    from grader.laps import distance_to
    from simiam.trace import EndReason

    config = get_week(5)
    world = load_world(config.world)
    solution = load_submission(ROOT / "solutions" / "week5", config)
    hidden = {(tuple(v["start"]), tuple(v["goal"]), v["mode"]) for v in load_hidden(5)["variants"]}
    inner = [p for p in world.obstacles if max(abs(c) for q in p for c in q) < 1.3]  # not the arena walls

    def free(point: tuple[float, float], away: float) -> bool:
        return (max(abs(point[0]), abs(point[1])) <= 1.4 - away
                and distance_to(point, world.obstacles) >= away
                and not any(_inside(point, poly) for poly in inner))

    def figures(mode: str, start: tuple, goal: tuple) -> dict | None:
        w, g, settings, first, _ = setup(config, mode, goal, start)
        trace = Simulator(w, LocalBrain(solution, config, settings), config.spec, dt=config.dt).run(
            config.seconds, until=lambda rec: math.dist(rec.pose[:2], g) < D_STOP)
        if trace.collision is not None or trace.ending is None or trace.ending.reason is not EndReason.UNTIL:
            return None
        names = [first, *trace.steps["state"][1:]]
        rate = sum(a != b for a, b in zip(names, names[1:], strict=False)) / trace.ending.t
        return {"time_to_goal": round(trace.ending.t, 2),
                "min_clearance": round(min_clearance(trace, w, config.spec) or 0.0, 3),
                "switch_rate": round(rate, 2)}

    rng = random.Random("practice:week5")
    variants: list[dict[str, Any]] = []
    for mode in ("blending", "switching"):
        while sum(1 for v in variants if v["mode"] == mode) < COUNT[5] // 2:
            start = (round(rng.uniform(-1.3, 1.3), 2), round(rng.uniform(-1.3, 1.3), 2),
                     round(rng.uniform(-math.pi, math.pi), 2))
            goal = (round(rng.uniform(-1.3, 1.3), 2), round(rng.uniform(-1.3, 1.3), 2))
            if (not free(start[:2], 0.2) or not free(goal, 0.25) or math.dist(start[:2], goal) < 1.0
                    or (start, goal, mode) in hidden):
                continue
            seen = figures(mode, start, goal)
            if (seen and seen["time_to_goal"] <= 45.0 and seen["min_clearance"] >= 0.03
                    and seen["switch_rate"] <= 1.5):
                variants.append({"mode": mode, "start": list(start), "goal": list(goal), "reference": seen})
    _write(5, (
        "Week-5 practice variants (not graded): the robot starts at `start` (x, y, theta in the "
        "week-5 world; the grader runs the world seen from that pose) and goes to `goal`, blending "
        "or switching (`mode`). Drawn by the rules of official grading's hidden variants (at least "
        "0.2 m and 0.25 m from every obstacle, 1 m apart) from another random stream, none of them a "
        "hidden one. Made by python -m instructor_tools.practice_sets 5: the reference solution "
        "reached each goal in at most 45 s, never closer than 0.03 m to an obstacle, switching at "
        "most 1.5 times per second (`reference` holds its figures). Official grading runs 3 other "
        "variants of each mode, from the instructor's hidden set."),
        variants)


def _inside(point: tuple[float, float], poly) -> bool:
    """Whether `point` is inside the polygon `poly` (even-odd rule)."""
    x, y = point
    inside = False
    for (x1, y1), (x2, y2) in zip(poly, [*poly[1:], poly[0]], strict=True):
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


# ------------------------------------------------------------------------------------------------ week 6
def week6() -> None:
    from instructor_tools.hidden_week6 import D_FW, HEADINGS, MARGIN, MAX_T, MIN_CLEARANCE, reference_run
    from instructor_tools.hidden_week6 import with_margin as kept_by_hidden_rules

    hidden = {(v["direction"], round(v["theta0"], 9), v["d_fw"]) for v in load_hidden(6)["variants"]}
    kept = []
    for direction in ("left", "right"):
        for k in range(HEADINGS):
            theta0 = (k + 0.5) * 2 * math.pi / HEADINGS
            for d_fw in D_FW:
                if (direction, round(theta0, 9), d_fw) in hidden:
                    continue
                ok, why, seen = reference_run(direction, theta0, d_fw)
                keep = ok and kept_by_hidden_rules(seen, d_fw)
                print(f"week 6 {direction} {theta0:.4f} {d_fw}: {'kept' if keep else 'dropped'} ({why})",
                      flush=True)
                if keep:
                    kept.append({"direction": direction, "theta0": theta0, "d_fw": d_fw})
    picks = draw(kept, COUNT[6], "practice:week6", lambda v: (v["direction"], heading_quarter(v["theta0"])))
    _write(6, (
        "Week-6 practice variants (not graded): follow the wall on `direction`, the robot starting at "
        "(0, 0, theta0), at the distance d_fw; the start headings lie halfway between those of official "
        "grading's hidden variants. Made by python -m instructor_tools.practice_sets 6 with the hidden set's "
        f"own rules: the reference solution made two laps within {MAX_T:g} s of the 90 s, kept within "
        f"{MARGIN} m of d_fw (median) and never came closer than {MIN_CLEARANCE} m to the obstacles. "
        "Official grading runs 3 other variants, from the instructor's hidden set."), picks)


MAKERS: dict[int, Callable[[], None]] = {3: week3, 4: week4, 5: week5, 6: week6}


def main(argv: list[str] | None = None) -> int:
    weeks = [int(a) for a in (sys.argv[1:] if argv is None else argv)] or sorted(MAKERS)
    for week in weeks:
        MAKERS[week]()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
