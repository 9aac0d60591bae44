"""Make (and check) the week-6 hidden set: lap runs on either side, from other start headings, at other d_fw.

    python -m instructor_tools.hidden_week6          # rewrite instructor_tools/hidden/week6.json

A candidate (side, start heading k*pi/6, d_fw) is kept only if the reference solution (solutions/week6)
passes the grader's own lap judgement on it with a margin: two laps by MAX_T of the 90 s, the median
distance within MARGIN of d_fw (the check allows 0.05 m), and never closer than MIN_CLEARANCE to the
obstacles (the check fails a touch). tests/grader/test_hidden_week6.py re-checks every kept variant with
the grader's judgement and these margins.

The clearance margin came with issue 20: at d_fw = 0.15 m on the left the reference passes the L's
corners 0.5 to 2 mm from the wall at every start heading, so whether it "collides" there is a matter of
the last bits; those variants are dropped.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from grader.checks.week6 import SECONDS, judge_laps, laps_done, obstacle, run_settings
from grader.scenarios import min_clearance
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "instructor_tools" / "hidden" / "week6.json"
MAX_T = 75.0
MARGIN = 0.03
MIN_CLEARANCE = 0.01  # m, at every step (grader.scenarios.min_clearance)
HEADINGS = 12
D_FW = (0.15, 0.18, 0.2)


def reference_run(direction: str, theta0: float, d_fw: float, folder: Path = ROOT / "solutions" / "week6"):
    """(passed, why, figures) of the grader's lap judgement on the code in `folder` for one variant."""
    week = get_week(6)
    world = load_world(week.world)
    sub = load_submission(folder, week)
    if not sub.ok:
        raise RuntimeError(f"{folder} does not load: {sub.errors[0]}")
    brain = LocalBrain(sub, week, run_settings(direction, theta0, d_fw))
    start = (0.0, 0.0, theta0)
    trace = Simulator(world, brain, week.spec, dt=week.dt, start=start).run(
        SECONDS, until=laps_done(direction)(start))  # as the check: the run ends once the laps are done
    ok, why, figures = judge_laps(trace.steps, trace.collision, direction, d_fw, obstacle(world), week.dt)
    gap = 0.0 if trace.collision is not None else min_clearance(trace, world, week.spec)
    return ok, why, {**figures, "min_clearance": gap}


def with_margin(figures: dict, d_fw: float) -> bool:
    return (
        figures["t_laps"] is not None
        and figures["t_laps"] <= MAX_T
        and abs(figures["median_distance"] - d_fw) <= MARGIN
        and figures["min_clearance"] >= MIN_CLEARANCE
    )


def main() -> int:
    variants = []
    for direction in ("left", "right"):
        for k in range(HEADINGS):
            theta0 = k * 2 * math.pi / HEADINGS
            for d_fw in D_FW:
                ok, why, figures = reference_run(direction, theta0, d_fw)
                keep = ok and with_margin(figures, d_fw)
                verdict = "kept" if keep else "dropped"
                print(f"{direction:5} heading {k:2}/{HEADINGS} d_fw {d_fw}: {verdict} ({why})")
                if keep:
                    variants.append({"direction": direction, "theta0": theta0, "d_fw": d_fw})
    data = {
        "about": (
            "Week-6 hidden variants: follow the wall on `direction`, the robot (true pose and estimate) "
            "starting at (0, 0, theta0), at the distance d_fw. Made by python -m "
            "instructor_tools.hidden_week6: the reference solution made two laps within "
            f"{MAX_T:g} s of the {SECONDS:g} s, kept within {MARGIN} m of d_fw (median) and never came "
            f"closer than {MIN_CLEARANCE} m to the obstacles in every one; tests/grader/test_hidden_week6.py "
            "re-checks them. A grading seed picks 3."
        ),
        "variants": variants,
    }
    OUT.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    print(f"{len(variants)} variants written to {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
