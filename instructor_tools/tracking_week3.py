"""Make the goals week 3's hidden tracking check never draws: where a correct controller has no margin.

    python -m instructor_tools.tracking_week3   # rewrites grader/checks/expected/week3_tracking_excluded.json

week3.pid.tracking_other_goal draws one goal per seed from a 0.01 m grid (grader.checks.week3.seeded_goals:
at least 0.5 m away, a turn of 1.0-2.2 rad from the start) and holds the run to the course's part-3.2 limits
(settle within 3 s, overshoot at most 10 %). Those limits were written for the course's goal (0, -1); over
the 13,740 goals of the grid the reference solution's overshoot scatters up to 18 % (it is measured on
the true heading against a moving bearing, a tick of heading at a time), and 104 goals failed it: one
seed in about 130 failed the reference itself. A goal stays drawable only if the reference solution and a
correct alternative with other gains (tests/data/wrong/good_week3_other_gains.patch) both settle by
SETTLE_MAX and overshoot at most OVERSHOOT_MAX: 1 s and 3 points of overshoot under the limits.
"""

from __future__ import annotations

import json
import math
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from grader.checks.week3 import (
    EXCLUDED_FILE,
    OVERSHOOT_LIMIT,
    ROBOT_D_STOP,
    SETTLE_LIMIT,
    TRACKING_TURN,
    drawable,
)
from grader.platforms.wrong_versions import apply_mistake
from grader.scenarios import settle_and_overshoot
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[1]
ALTERNATIVE = ROOT / "tests" / "data" / "wrong" / "good_week3_other_gains.patch"
SETTLE_MAX = SETTLE_LIMIT - 1.0      # s
OVERSHOOT_MAX = OVERSHOOT_LIMIT - 0.03


def grid() -> list[tuple[float, float]]:
    """Every goal seeded_goals can draw for the tracking check."""
    out = []
    for i in range(-110, 111):
        for j in range(-110, 111):
            g = (round(i / 100, 2), round(j / 100, 2))
            if drawable(g, TRACKING_TURN):
                out.append(g)
    return out


def tracking(folder: Path, goal: tuple[float, float]) -> tuple[float | None, float]:
    """(settle time, overshoot) of `folder`'s controller toward `goal`, as the check runs and measures it."""
    week = get_week(3)
    sub = load_submission(folder, week)
    settings = week.settings.with_changes(goal=list(goal), d_stop=ROBOT_D_STOP, state="go_to_goal")
    sim = Simulator(load_world(week.world), LocalBrain(sub, week, settings.as_dict()), week.spec, dt=week.dt)
    trace = sim.run(week.seconds, until=lambda rec: math.dist(rec.pose[:2], goal) < week.settings.d_stop)
    return settle_and_overshoot(trace, goal)


def with_margin(seen: tuple[float | None, float]) -> bool:
    settle, overshoot = seen
    return settle is not None and settle <= SETTLE_MAX and overshoot <= OVERSHOOT_MAX


def _excluded(goals: list[tuple[float, float]]) -> list[tuple[float, float]]:
    with tempfile.TemporaryDirectory() as tmp:
        alternative = apply_mistake(ALTERNATIVE, ROOT / "solutions", Path(tmp) / "alternative")[1]
        folders = (ROOT / "solutions" / "week3", alternative)
        return [g for g in goals if not all(with_margin(tracking(f, g)) for f in folders)]


def main() -> int:
    goals = grid()
    with ProcessPoolExecutor(max_workers=2) as pool:
        excluded = sorted(g for part in pool.map(_excluded, [goals[0::2], goals[1::2]]) for g in part)
    about = " ".join(__doc__.split("\n\n")[2].split())
    head = json.dumps({"about": about, "settle_max": SETTLE_MAX, "overshoot_max": OVERSHOOT_MAX})[:-1]
    rows = ",\n".join(json.dumps(list(g)) for g in excluded)  # a goal a line: diffs stay readable
    EXCLUDED_FILE.write_text(f'{head},\n"excluded": [\n{rows}\n]}}\n', encoding="utf-8")
    print(f"{len(excluded)} of {len(goals)} goals excluded, written to {EXCLUDED_FILE}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
