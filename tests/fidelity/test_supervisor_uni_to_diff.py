"""The solutions' differential_drive against the original's recordings (uni_to_diff.csv, diff_to_uni.csv).

Every row to 1e-12, for each week that ships the module filled in (2, 3, 4); wrong versions must fail.
"""

from __future__ import annotations

import csv
from pathlib import Path

import mistakes
import pytest

from simiam.control import RobotView
from simiam.course.loader import load_submission
from simiam.course.weeks import spec_for_week

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests/data/golden"
TOL = 1e-12


def _rows(name: str) -> list[dict]:
    with (GOLDEN / name).open() as f:
        return list(csv.DictReader(f))


def _folder(tmp_path: Path, week: int, mutant: str | None) -> Path:
    if mutant is None:
        return ROOT / f"solutions/week{week}"
    return mistakes.build("submissions", mutant, tmp_path, week)


def worst_errors(folder: Path, week: int) -> tuple[float, float]:
    """Largest error of uni_to_diff and of diff_to_uni over every recorded row."""
    u2d, d2u, _ = _compare(folder, week)
    return u2d, d2u


def _compare(folder: Path, week: int) -> tuple[float, float, int]:
    """Worst uni_to_diff error, worst diff_to_uni error, and how many rows are not bit-identical."""
    sub = load_submission(folder, week)
    assert sub.ok, sub.errors
    robot = RobotView(spec_for_week(week), sub)
    drive = sub.module("differential_drive")
    u2d = d2u = 0.0
    not_exact = 0
    for row in _rows("uni_to_diff.csv"):
        got = drive.uni_to_diff(robot, float(row["v"]), float(row["w"]))
        u2d = max(u2d, abs(got[0] - float(row["vel_r"])), abs(got[1] - float(row["vel_l"])))
        not_exact += tuple(got) != (float(row["vel_r"]), float(row["vel_l"]))
    for row in _rows("diff_to_uni.csv"):
        got = drive.diff_to_uni(robot, float(row["vel_r"]), float(row["vel_l"]))
        d2u = max(d2u, abs(got[0] - float(row["v"])), abs(got[1] - float(row["w"])))
        not_exact += tuple(got) != (float(row["v"]), float(row["w"]))
    return u2d, d2u, not_exact


@pytest.mark.parametrize("week", [2, 3, 4])
def test_solutions_reproduce_every_recorded_row(week):
    u2d, d2u = worst_errors(ROOT / f"solutions/week{week}", week)
    assert u2d <= TOL, f"uni_to_diff off by {u2d:.3g}"
    assert d2u <= TOL, f"diff_to_uni off by {d2u:.3g}"


@pytest.mark.parametrize("week", [2, 3, 4])
def test_solutions_keep_the_original_operation_order(week):
    """Bit-identical, not just within 1e-12: the week-4 ensure_w feeds these into the strict dead zone,
    where one ulp decides whether a wheel is zeroed (reference/original-simulator.md 4.3)."""
    assert _compare(ROOT / f"solutions/week{week}", week)[2] == 0


def test_reordered_arithmetic_is_caught(tmp_path):
    u2d, d2u, not_exact = _compare(_folder(tmp_path, 4, "week4_diff_to_uni_reordered"), 4)
    assert d2u <= TOL and not_exact > 0
