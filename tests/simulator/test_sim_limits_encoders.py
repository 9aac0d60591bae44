"""limit_speeds (clamp, then the strict dead zone at 30*2*pi/60) and the encoder's rounding and carry."""

from __future__ import annotations

import math

import pytest
from sim_helpers import wrong

from simiam.course.weeks import spec_for_week
from simiam.robot.quickbot import MIN_VEL_30RPM, limit_speeds
from simiam.robot.wheel_encoder import WheelEncoder

W4 = spec_for_week(4)


def dead_zone_problems(limit) -> list:
    mx, mn = W4.max_vel, W4.min_vel
    cases = [
        ((mn, -mn), (mn, -mn)),                                   # exactly min_vel: kept (strict test)
        ((math.nextafter(mn, 0), 5.0), (0.0, 5.0)),               # one ulp below: zeroed
        ((-math.nextafter(mn, 0), -5.0), (0.0, -5.0)),
        ((math.pi, 1.0), (math.pi, 0.0)),                         # pi is one ulp above min_vel
        ((20.0, -20.0), (mx, -mx)),                               # clamp
        ((0.5, 1e9), (0.0, mx)),
    ]
    return [(args, limit(*args, mx, mn), want) for args, want in cases if limit(*args, mx, mn) != want]


def test_min_vel_is_one_ulp_below_pi():
    assert MIN_VEL_30RPM == math.nextafter(math.pi, 0) == W4.min_vel


def test_dead_zone_is_strict():
    assert dead_zone_problems(limit_speeds) == []


@pytest.mark.parametrize("name", ["non_strict", "dead_zone_first", "no_dead_zone"])
def test_dead_zone_check_catches(name):
    assert dead_zone_problems(getattr(wrong("limits_wrong"), name))


def test_weeks_1_to_3_have_no_dead_zone():
    for week in (1, 2, 3):
        spec = spec_for_week(week)
        assert spec.limit_speeds(0.1, -9.0) == (0.1, -80 * 2 * math.pi / 60)


# the wheel angle whose tick count the encoder computes as exactly 0.5 - 2**-54 (the largest double below
# 0.5): floor(x + 0.5) counts it as 1, because x + 0.5 rounds up to 1.0 before the floor
JUST_BELOW_HALF_TICK = math.nextafter(math.pi / 16, 0)


def test_just_below_half_a_tick_is_the_largest_double_below_half():
    assert JUST_BELOW_HALF_TICK * 16 / (2 * math.pi) == 0.5 - 2 ** -54 == math.nextafter(0.5, 0)


def encoder_problems(cls) -> list:
    out = []
    e = cls(16)
    e.update(math.pi / 16, 1.0)                 # exactly half a tick: rounds away from zero
    if e.ticks != 1:
        out.append(("half tick", e.ticks))
    e = cls(16)
    e.update(-math.pi / 16, 1.0)
    if e.ticks != -1:
        out.append(("minus half tick", e.ticks))
    e = cls(16)
    e.update(JUST_BELOW_HALF_TICK, 1.0)         # 0.5 - 2**-54 of a tick: MATLAB's round gives 0
    if e.ticks != 0:
        out.append(("just below half a tick", e.ticks))
    e = cls(16)
    e.update(-JUST_BELOW_HALF_TICK, 1.0)
    if e.ticks != 0:
        out.append(("just below minus half a tick", e.ticks))
    e = cls(16)
    tick = 2 * math.pi / 16
    seen = []
    for _ in range(5):                          # 0.4 tick per step: the remainder carries over
        e.update(0.4 * tick, 1.0)
        seen.append(e.ticks)
    if seen != [0, 1, 1, 2, 2]:
        out.append(("carry", seen))
    return out


def test_encoder_rounding_and_carry():
    assert encoder_problems(WheelEncoder) == []


@pytest.mark.parametrize("name", ["encoder_no_carry", "encoder_bankers"])
def test_encoder_check_catches(name):
    assert encoder_problems(wrong(name).WheelEncoder)
