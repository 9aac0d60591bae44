"""Week 1: the simulator runs and the robot stays still (the manual, section 4.1)."""

from __future__ import annotations

from pathlib import Path

import mistakes

from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
WEEK = get_week(1)


def _folder(tmp_path: Path, mutant: str | None) -> Path:
    if mutant is None:
        return ROOT / "solutions/week1"
    return mistakes.build("submissions", mutant, tmp_path, 1)


def moved(folder: Path) -> float:
    """How far (m) the robot got from its start in the week's 5 s scenario (0 if it never moved)."""
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    sim = Simulator(load_world(WEEK.world), LocalBrain(sub, WEEK), WEEK.spec, dt=0.033)
    trace = sim.run(WEEK.seconds)
    s = trace.steps
    assert trace.collision is None
    assert s["state"][-1] == "stop"
    columns = ("x", "y", "theta", "ticks_r", "ticks_l")
    return max(sum(abs(s[c][k]) for c in columns) for k in range(len(trace)))


def test_robot_stays_still():
    assert moved(ROOT / "solutions/week1") == 0.0


def test_a_moving_robot_is_caught(tmp_path):
    assert moved(_folder(tmp_path, "week1_moves")) > 0.0
