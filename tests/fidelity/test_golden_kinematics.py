"""uni_to_diff / diff_to_uni against the recordings: <= 1e-12, and bit-exact (the original's operation
order is what makes the dead-zone rounding quirk reproduce)."""

from __future__ import annotations

import pytest
from physics_golden import check_kinematics, wrong

from instructor_tools.reference_maths import uni_to_diff
from simiam.robot.dynamics import diff_to_uni
from simiam.robot.quickbot import WHEEL_BASE_LENGTH as L
from simiam.robot.quickbot import WHEEL_RADIUS as R

U2D = ("uni_to_diff.csv", ("v", "w"), ("vel_r", "vel_l"))
D2U = ("diff_to_uni.csv", ("vel_r", "vel_l"), ("v", "w"))


@pytest.mark.parametrize("fn,table", [(uni_to_diff, U2D), (diff_to_uni, D2U)],
                         ids=["uni_to_diff", "diff_to_uni"])
def test_reference_kinematics(fn, table):
    res = check_kinematics(fn, *table, R, L)
    assert res["rows"] > 0
    assert res["max_error"] <= 1e-12, res
    assert res["not_bit_exact"] == 0, res


@pytest.mark.parametrize("name,table", [("uni_to_diff_swapped", U2D), ("diff_to_uni_no_half", D2U)])
def test_tolerance_check_catches(name, table):
    assert check_kinematics(getattr(wrong("kinematics_wrong"), name), *table, R, L)["max_error"] > 1e-12


@pytest.mark.parametrize("name,table", [("uni_to_diff_reordered", U2D), ("diff_to_uni_reordered", D2U)])
def test_bit_exact_check_catches_reordering(name, table):
    res = check_kinematics(getattr(wrong("kinematics_wrong"), name), *table, R, L)
    assert res["max_error"] <= 1e-12 and res["not_bit_exact"] > 0
