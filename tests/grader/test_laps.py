"""Laps at a gate (grader/laps.py): a full turn around the obstacle counts once, in the running direction
only; wobbling on the gate, starting on it, or passing beside it counts nothing. The original's disc counter
(kept below as the wrong version) counts a wobble at the start as laps."""

from __future__ import annotations

import math

from grader.checks.week6 import gate
from grader.laps import Gate, distance_to, laps, median_distance

SQUARE = [[(-0.2, 0.2), (0.4, 0.2), (0.4, 0.4), (-0.2, 0.4)]]


def circle(turns: float, sign: int = 1, n: int = 400) -> tuple[list[float], list[float]]:
    """A path around (0.1, 0.3) starting at (0, 0) below it: anticlockwise for sign +1."""
    cx, cy, r = 0.1, 0.3, math.hypot(0.1, 0.3)
    start = math.atan2(-cy, -cx)
    angles = [start + sign * 2 * math.pi * turns * k / n for k in range(1, n + 1)]
    return [0.0] + [cx + r * math.cos(a) for a in angles], [0.0] + [cy + r * math.sin(a) for a in angles]


def disc_laps(xs: list[float], ys: list[float]) -> int:
    """The original test's counter: +1 each time the robot leaves the 0.1 m disc around the start."""
    count, armed = 0, True
    for x, y in zip(xs, ys, strict=True):
        r = math.hypot(x, y)
        if armed and r > 0.1:
            count, armed = count + 1, False
        elif r < 0.1:
            armed = True
    return count


def test_each_turn_in_the_running_direction_is_one_lap():
    xs, ys = circle(2.2)
    assert laps(xs, ys, gate("left"))[-1] == 2
    xs, ys = circle(2.2, sign=-1)
    assert laps(xs, ys, gate("right"))[-1] == 2


def test_turns_against_the_running_direction_take_laps_away():
    xs, ys = circle(2.2, sign=-1)
    # the start on the gate counts as past it: the first step backwards crosses it too
    assert laps(xs, ys, gate("left"))[-1] == -3


def test_starting_on_the_gate_and_going_back_first_counts_nothing():
    # the robot starts at x = 0 on the gate, backs off to x < 0, comes forward again past it
    xs = [0.0, -0.01, -0.02, -0.01, 0.0, 0.01, 0.05]
    ys = [0.0] * len(xs)
    assert laps(xs, ys, gate("left"))[-1] == 0


def test_a_wobble_on_the_gate_nets_zero():
    xs = [0.0] + [0.11 * (-1) ** k for k in range(1, 12)]
    ys = [0.0] * len(xs)
    counted = laps(xs, ys, gate("left"))
    assert max(counted) == 0 and counted[-1] == -1  # back and forth across the gate: never a lap


def test_a_wobble_at_the_start_is_no_lap_but_the_disc_counter_counts_it():
    xs = [0.0] + [0.05, 0.12] * 6  # in and out of the 0.1 m disc, never around the obstacle
    ys = [0.0] * len(xs)
    assert max(laps(xs, ys, gate("left"))) == 0
    assert disc_laps(xs, ys) > 2  # the original test would have passed this robot


def test_passing_beside_the_gate_is_not_a_crossing():
    g = Gate(0.0, -1.4, 0.2, 1)
    assert g.crossing((-0.1, 0.5), (0.1, 0.5)) == 0  # above the obstacle's edge: not on the gate
    assert g.crossing((-0.1, -1.0), (0.1, -1.0)) == 1
    assert g.crossing((0.1, -1.0), (-0.1, -1.0)) == -1


def test_distance_to_the_obstacle():
    assert distance_to((0.1, 0.0), SQUARE) == 0.2
    assert distance_to((0.6, 0.3), SQUARE) == 0.19999999999999996
    assert median_distance([0.1, 0.1, 0.1], [0.0, -0.1, -0.2], SQUARE, every=1) == 0.30000000000000004
