"""ensure_w of the solutions against the original's recordings (tests/data/golden/ensure_w.csv).

Every row of every version in the file: `week3` (solutions/week3, 80 rpm), `week3_maxrpm130` (the same
code on a robot with max_vel = 130 rpm) and `week4` (the provided dead-zone ensure_w of solutions/week4).
The recording is ensure_w's output before the motors' limits; for week 4 the limited speeds must also
zero exactly the same wheels, because a wheel a few ulp under min_vel is what the dead zone catches.
Wrong versions in tests/data/submissions/ must fail.
"""

from __future__ import annotations

import csv
import dataclasses
from collections import defaultdict
from pathlib import Path

import mistakes
import pytest

from simiam.control import Pose2D, RobotView
from simiam.course.loader import load_submission
from simiam.course.weeks import spec_for_week
from simiam.robot.quickbot import limit_speeds

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests/data/golden/ensure_w.csv"
WEEK_OF_VERSION = {"week3": 3, "week3_maxrpm130": 3, "week4": 4}
TOL = 1e-12


def _rows_by_version() -> dict[str, list[dict]]:
    by_version: dict[str, list[dict]] = defaultdict(list)
    with GOLDEN.open() as f:
        for row in csv.DictReader(f):
            by_version[row["version"]].append(row)
    return by_version


ROWS = _rows_by_version()


def _folder(tmp_path: Path, week: int, mutant: str | None) -> Path:
    """solutions/weekN, or a copy of it with tests/data/submissions/<mutant>.patch applied."""
    if mutant is None:
        return ROOT / f"solutions/week{week}"
    return mistakes.build("submissions", mutant, tmp_path, week)


def mismatches(folder: Path, version: str) -> list[str]:
    """The rows of `version` where the folder's ensure_w differs from the recording."""
    week = WEEK_OF_VERSION[version]
    sub = load_submission(folder, week)
    assert sub.ok, sub.errors
    bad = []
    for row in ROWS[version]:
        # the robot the recording used: max_vel (80 or 130 rpm) and min_vel (0 = no dead zone)
        spec = dataclasses.replace(spec_for_week(week), max_vel=float(row["vel_max"]),
                                   min_vel=float(row["vel_min"]))
        robot = RobotView(spec, sub)
        supervisor = sub.module("qb_supervisor").QBSupervisor()
        supervisor.attach_robot(robot, Pose2D(0.0, 0.0, 0.0))
        v, w = float(row["v"]), float(row["w"])
        vel_r, vel_l = supervisor.ensure_w(robot, v, w)
        want_r, want_l = float(row["vel_r"]), float(row["vel_l"])
        err = max(abs(vel_r - want_r), abs(vel_l - want_l))
        limited = limit_speeds(vel_r, vel_l, spec.max_vel, spec.min_vel)
        want_limited = limit_speeds(want_r, want_l, spec.max_vel, spec.min_vel)
        zeroed_differs = [a == 0.0 for a in limited] != [b == 0.0 for b in want_limited]
        if err > TOL or zeroed_differs:
            bad.append(f"v={v} w={w}: got ({vel_r!r}, {vel_l!r}), recorded ({want_r!r}, {want_l!r})")
    return bad


@pytest.mark.parametrize("version", sorted(ROWS))
def test_solutions_reproduce_every_recorded_row(version):
    assert version in WEEK_OF_VERSION, f"unknown version {version!r} in ensure_w.csv"
    assert ROWS[version], version
    bad = mismatches(ROOT / f"solutions/week{WEEK_OF_VERSION[version]}", version)
    assert not bad, f"{len(bad)} of {len(ROWS[version])} rows differ, e.g. {bad[:3]}"


@pytest.mark.parametrize(
    ("mutant", "version"),
    [
        ("week3_ensure_w_no_shift", "week3"),  # the stub's placeholder: w not ensured
        ("week3_ensure_w_no_shift", "week3_maxrpm130"),
        ("week3_ensure_w_wrong_sign", "week3"),  # reverse shift added the wrong way round
        ("week4_ensure_w_no_sign_fix", "week4"),  # shifted speeds returned without the sign fix
    ],
)
def test_wrong_ensure_w_is_caught(tmp_path, mutant, version):
    folder = _folder(tmp_path, WEEK_OF_VERSION[version], mutant)
    assert mismatches(folder, version), f"{mutant} was not caught on {version}"
