"""Scenario metrics computed the course's way (original-simulator.md section 7, part 3.2)."""

from __future__ import annotations

import math
from pathlib import Path

from grader.grading import grade_submission
from grader.scenarios import max_displacement, path_length, settle_and_overshoot
from simiam.trace import Trace

ROOT = Path(__file__).resolve().parents[2]


def _trace(thetas: list[float], dt: float = 0.05) -> Trace:
    """A robot that turns on the spot at the origin: the goal heading r stays fixed."""
    trace = Trace(week=3, dt=dt, world={"name": "t", "obstacles": []}, robot={}, start=[0.0, 0.0, 0.0])
    n = len(thetas)
    trace.steps.update({"t": [k * dt for k in range(n)], "x": [0.0] * n, "y": [0.0] * n, "theta": thetas})
    return trace


def test_settle_is_the_start_of_21_samples_inside_10_percent() -> None:
    r = -math.pi / 2
    thetas = [0.0] * 10 + [r * 0.95] * 30   # inside the band from sample 10 on
    settle, overshoot = settle_and_overshoot(_trace(thetas), (0.0, -1.0))
    assert settle == 10 * 0.05
    assert math.isclose(overshoot, 0.05)     # min(y) = 0.95 r: the course takes |r - y| / |r| there


def test_a_dip_outside_the_band_restarts_the_count_and_overshoot_is_the_extreme() -> None:
    r = -math.pi / 2
    thetas = [r] * 20 + [r * 1.3] + [r] * 25  # one sample 30 % past r: the count starts again
    settle, overshoot = settle_and_overshoot(_trace(thetas), (0.0, -1.0))
    assert settle == 21 * 0.05
    assert math.isclose(overshoot, 0.3)
    never, _ = settle_and_overshoot(_trace([0.0] * 50), (0.0, -1.0))
    assert never is None


def test_heading_is_wrapped_before_comparing() -> None:
    r = -math.pi / 2
    settle, _ = settle_and_overshoot(_trace([r + 4 * math.pi] * 25), (0.0, -1.0))
    assert settle == 0.0


def test_path_length_and_displacement() -> None:
    trace = _trace([0.0] * 3)
    trace.steps["x"] = [0.0, 3.0, 0.0]
    trace.steps["y"] = [0.0, 4.0, 0.0]
    assert path_length(trace) == 10.0 and max_displacement(trace) == 5.0


def test_hidden_checks_say_when_the_hidden_set_is_missing(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv("SIMIAM_HIDDEN", str(tmp_path))
    result = grade_submission(4, ROOT / "solutions" / "week4", seed=1, hidden=True,
                              only="week4.avoid.other_starts")
    check = result["checks"][0]
    assert check["status"] == "error" and "hidden set is not here" in check["message"]


def test_overshoot_wraps_the_angle_difference() -> None:
    """A goal bearing just below pi: the heading reaches it from the other side of +-pi. Unwrapped, the
    heading 3.1 at the extreme sample against a bearing of -3.09 read as 200 % overshoot."""
    goal = (-1.0, 0.0)
    trace = _trace([0.0, 1.0, 2.0, 3.0, 3.1])
    trace.steps["y"] = [-0.05] * 4 + [0.05]  # the robot drifts across the line to the goal
    settle, overshoot = settle_and_overshoot(trace, goal)
    bearing = math.atan2(-0.05, -1.0)
    assert overshoot == abs(math.atan2(math.sin(bearing - 3.1), math.cos(bearing - 3.1))) / abs(bearing)
    assert overshoot < 0.05
