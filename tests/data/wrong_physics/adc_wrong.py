"""WRONG distance -> raw maps, each `raw(d, ir_mode)`."""
import math

from simiam.robot.ir_sensor import ir_voltage


def original_week2_polynomial(d, ir_mode):
    """The original's week-2 polynomial, which contradicts its own table (0.04 m -> 1330)."""
    p2 = (-5.3245e6, 5.4518e6, -2.2089e6, 0.4511e6, -0.0491e6, 0.0027e6)
    v = 0.0
    for c in p2:
        v = v * d + c
    return min(max(math.floor(v + 0.5), 200), 1375)


def floor_not_round(d, ir_mode):
    """The sp15 manual's floor instead of the code's round."""
    if ir_mode == "week2":
        return min(max(math.floor(ir_voltage(d) * 500), 200), 1375)
    return min(max(math.floor(ir_voltage(d) * 1000 / 3), 133), 917)


def week3_divider_everywhere(d, ir_mode):
    """Ignores the week-2 divider."""
    return min(max(math.floor(ir_voltage(d) * 1000 / 3 + 0.5), 133), 917)
