"""The provided code of every week accepts any real number a student's block may produce: Python ints,
floats and bools, and numpy scalars (a numpy float's comparisons give numpy bools, which numpy refuses to
subtract: the week-4 `sign()` once raised on them and cost a correct controller 2 points)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from simiam.control import Pose2D, RobotView
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week, week_numbers

ROOT = Path(__file__).resolve().parents[2]
KINDS = {
    "int": int,
    "bool": bool,
    "numpy float64": np.float64,
    "numpy float32": np.float32,
    "numpy int64": np.int64,
    "numpy bool": np.bool_,
}
VALUES = [(0.1, 0.5), (-0.2, -3.0), (0.0, 1.0), (1.0, 0.0), (0.0, 0.0), (10.0, -40.0)]


def _as(kind, x: float):
    if kind in (bool, np.bool_):
        return kind(x != 0)
    return kind(x) if kind in (np.float64, np.float32) else kind(round(x))


def _loaded(week: int):
    sub = load_submission(ROOT / "solutions" / f"week{week}", get_week(week))
    assert sub.ok, sub.errors
    robot = RobotView(get_week(week).spec, sub)
    return sub, robot


def _same(got, want) -> None:
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        assert math.isclose(float(g), float(w), rel_tol=1e-6, abs_tol=1e-9), (got, want)


@pytest.mark.parametrize("week", week_numbers())
@pytest.mark.parametrize("kind", list(KINDS), ids=list(KINDS))
def test_provided_kinematics_take_any_real_number(week: int, kind: str) -> None:
    sub, robot = _loaded(week)
    drive = sub.module("differential_drive")
    for v, w in VALUES:
        a, b = _as(KINDS[kind], v), _as(KINDS[kind], w)
        _same(drive.diff_to_uni(robot, a, b), drive.diff_to_uni(robot, float(a), float(b)))


@pytest.mark.parametrize("week", [3, 4])
@pytest.mark.parametrize("kind", list(KINDS), ids=list(KINDS))
def test_ensure_w_takes_any_real_number(week: int, kind: str) -> None:
    sub, robot = _loaded(week)
    sup = sub.module("qb_supervisor").QBSupervisor()
    sup.attach_robot(robot, Pose2D(0.0, 0.0, 0.0))
    for v, w in VALUES:
        a, b = _as(KINDS[kind], v), _as(KINDS[kind], w)
        _same(sup.ensure_w(robot, a, b), sup.ensure_w(robot, float(a), float(b)))


@pytest.mark.parametrize("kind", list(KINDS), ids=list(KINDS))
def test_week4_sign_takes_any_real_number(kind: str) -> None:
    sign = _loaded(4)[0].module("qb_supervisor").sign
    for x in (-2.5, -1.0, 0.0, 0.7, 3.0):
        value = _as(KINDS[kind], x)
        assert sign(value) == (float(value) > 0) - (float(value) < 0)
        assert type(sign(value)) is int
