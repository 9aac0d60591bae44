"""Week 2: uni_to_diff, odometry and the IR conversion of solutions/week2 do what the manual promises.

The robot turns to theta_d (GoToAngle) and the odometry estimate tracks the true pose; the IR conversion
reads the manual's table back within 3%. Wrong versions in tests/data/submissions/ must fail.
"""

from __future__ import annotations

import math
from pathlib import Path

import mistakes
import pytest

from simiam.control import RobotView
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.robot.ir_sensor import distance_to_raw
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]
WEEK = get_week(2)
TABLE_D = [0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10, 0.12, 0.14, 0.16, 0.18, 0.20, 0.25, 0.30]


def _folder(tmp_path: Path, mutant: str | None) -> Path:
    if mutant is None:
        return ROOT / "solutions/week2"
    return mistakes.build("submissions", mutant, tmp_path, 2)


def _wrap(a: float) -> float:
    return math.atan2(math.sin(a), math.cos(a))


def turn_and_track(folder: Path, theta_d: float, dt: float) -> tuple[float, float, float]:
    """Run 10 s toward theta_d: (final heading error, worst position error of the estimate, worst
    heading error of the estimate)."""
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    brain = LocalBrain(sub, WEEK, {"theta_d": theta_d, "v": 0.1})
    sim = Simulator(load_world(WEEK.world), brain, WEEK.spec, dt=dt)
    trace = sim.run(WEEK.seconds)
    assert trace.collision is None
    s = trace.steps
    pos_err = max(math.hypot(s["x_est"][k] - s["x"][k], s["y_est"][k] - s["y"][k]) for k in range(len(trace)))
    head_err = max(abs(_wrap(s["theta_est"][k] - s["theta"][k])) for k in range(len(trace)))
    return abs(_wrap(theta_d - s["theta"][-1])), pos_err, head_err


@pytest.mark.parametrize("theta_d", [math.pi / 4, -math.pi / 4, 0.0, 2.5])
@pytest.mark.parametrize("dt", [0.033, 0.05])
def test_turns_to_theta_d_and_odometry_tracks(theta_d, dt):
    final, pos_err, head_err = turn_and_track(ROOT / "solutions/week2", theta_d, dt)
    assert final < 0.05, f"heading ends {final:.3f} rad from theta_d"
    # one encoder tick of difference is 0.129 rad of heading: the estimate is within two ticks
    assert pos_err < 0.03 and head_err < 0.2, (pos_err, head_err)


def test_odometry_placeholder_is_caught(tmp_path):
    folder = _folder(tmp_path, "week2_odometry_placeholder")
    final, pos_err, head_err = turn_and_track(folder, math.pi / 4, 0.033)
    assert final > 0.05 or pos_err > 0.03 or head_err > 0.2


def ir_relative_errors(folder: Path) -> list[float]:
    """|d_est - d| / d for every distance of the manual's table, through the week-2 ADC."""
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    robot = RobotView(WEEK.spec, sub)
    errors = []
    for d in TABLE_D:
        robot.update({"ticks": [0, 0], "ir_raw": [distance_to_raw(d, WEEK.spec.ir_mode)] * 5})
        errors += [abs(e - d) / d for e in robot.get_ir_distances()]
    return errors


def test_ir_distances_read_the_table_back():
    assert max(ir_relative_errors(ROOT / "solutions/week2")) < 0.03


def test_week3_divider_in_week2_is_caught(tmp_path):
    assert max(ir_relative_errors(_folder(tmp_path, "week2_ir_week3_divider"))) > 0.03


def part2_answer(folder: Path, v: float, theta_d: float) -> str:
    """The course's part-2 answer: relative odometry errors in x, y, theta after 25 steps of 0.05 s."""
    sub = load_submission(folder, WEEK)
    assert sub.ok, sub.errors
    brain = LocalBrain(sub, WEEK, {"v": v, "theta_d": theta_d})
    sim = Simulator(load_world(WEEK.world), brain, WEEK.spec, dt=0.05)
    for _ in range(25):
        rec = sim.step()
    truth, est = rec.pose, rec.command["estimate"]
    return ", ".join(f"{abs((t - e) / t):.3f}" for t, e in zip(truth, est, strict=True))


@pytest.mark.parametrize(
    ("v", "theta_d", "answer"),
    # values from the reference's model of the original week 2 (original-simulator.md, section 11)
    [(0.1, math.pi / 4, "0.013, 0.011, 0.129"), (0.15, 0.5, "0.027, 0.006, 0.047")],
)
def test_part2_odometry_answer_matches_the_reference_model(v, theta_d, answer):
    assert part2_answer(ROOT / "solutions/week2", v, theta_d) == answer


def test_part2_answer_of_the_placeholder_differs(tmp_path):
    folder = _folder(tmp_path, "week2_odometry_placeholder")
    assert part2_answer(folder, 0.1, math.pi / 4) != "0.013, 0.011, 0.129"
