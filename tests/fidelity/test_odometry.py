"""update_odometry of the solutions against the original's recording (tests/data/golden/odometry.csv).

The recording fed a prescribed cumulative tick sequence to QBSupervisor.update_odometry (sp14, identical
in week 3) starting from (0, 0, 0); theta_est is wrapped with atan2. Every row must match to 1e-12, and the
wrong versions in tests/data/submissions/ must not.
"""

from __future__ import annotations

import csv
from pathlib import Path

import mistakes
import pytest

from simiam.control import Pose2D, RobotView
from simiam.course.loader import load_submission
from simiam.course.weeks import spec_for_week

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests/data/golden/odometry.csv"
TOL = 1e-12

with GOLDEN.open() as _f:
    ROWS = list(csv.DictReader(_f))


def _folder(tmp_path: Path, week: int, mutant: str | None) -> Path:
    if mutant is None:
        return ROOT / f"solutions/week{week}"
    return mistakes.build("submissions", mutant, tmp_path, week)


def worst_error(folder: Path, week: int) -> tuple[float, int]:
    """Largest |estimate - recording| over all rows, and the step where it happens."""
    sub = load_submission(folder, week)
    assert sub.ok, sub.errors
    robot = RobotView(spec_for_week(week), sub)
    supervisor = sub.module("qb_supervisor").QBSupervisor()
    supervisor.attach_robot(robot, Pose2D(0.0, 0.0, 0.0))
    worst, where = 0.0, -1
    for row in ROWS:
        if int(row["step"]) > 0:  # row 0 is the start, before any update
            robot.encoders[0].ticks = int(row["right_ticks"])
            robot.encoders[1].ticks = int(row["left_ticks"])
            supervisor.update_odometry()
        got = supervisor.state_estimate.unpack()
        want = (float(row["x_est"]), float(row["y_est"]), float(row["theta_est"]))
        err = max(abs(g - w) for g, w in zip(got, want, strict=True))
        if err > worst:
            worst, where = err, int(row["step"])
    return worst, where


@pytest.mark.parametrize("week", [3, 4])
def test_solutions_reproduce_every_recorded_row(week):
    assert len(ROWS) > 1
    err, step = worst_error(ROOT / f"solutions/week{week}", week)
    assert err <= TOL, f"week {week}: estimate off by {err:.3g} at step {step}"


@pytest.mark.parametrize(
    "mutant",
    [
        "week3_odometry_no_wrap",  # the week-2 template's unwrapped theta in week 3
        "week3_odometry_new_heading",  # x_dt, y_dt along the new heading theta + phi
    ],
)
def test_wrong_odometry_is_caught(tmp_path, mutant):
    err, _ = worst_error(_folder(tmp_path, 3, mutant), 3)
    assert err > TOL, f"{mutant} was not caught"
