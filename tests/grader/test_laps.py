"""Laps at a gate (simiam/laps.py, which `simiam run` and the week-6 checks share): a full turn around the
obstacle counts once, in the running direction only; wobbling on the gate, starting on it, or passing beside
it counts nothing. The original's disc counter (kept below as the wrong version) counts a wobble at the
start as laps. And the grader's other lap figure, the distance kept from the obstacle (grader/laps.py)."""

from __future__ import annotations

import math

import pytest

from grader.checks.week6 import gate
from grader.laps import distance_to, median_distance
from simiam.course.weeks import get_week
from simiam.laps import Gate, LapsDone, count_laps, laps

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


def test_the_checks_gate_is_the_one_week_6_declares():
    declared = get_week(6).lap_gate
    assert gate("left") == declared
    assert gate("right") == Gate(declared.x, declared.y_low, declared.y_high, -declared.sign)


def test_count_laps_follows_the_robot_round_either_way():
    """A student's own run may follow the wall on either side: the count takes the direction it went."""
    ts = [0.1 * k for k in range(401)]
    xs, ys = circle(2.2)
    counted = count_laps(xs, ys, ts, gate("left"))
    assert (counted.done, counted.gate.sign) == (2, 1)
    assert counted.times == (ts[laps(xs, ys, gate("left")).index(1)], ts[laps(xs, ys, gate("left")).index(2)])
    xs, ys = circle(2.2, sign=-1)
    counted = count_laps(xs, ys, ts, gate("left"))
    assert (counted.done, counted.gate.sign) == (2, -1)
    words = counted.words()
    assert words.startswith("Laps: 2 through the gate (x = 0 from y = -1.4 to 0.2, crossed toward -x)")


def test_no_lap_is_no_lap_either_way():
    xs = [0.0] + [0.05, 0.12] * 6
    counted = count_laps(xs, [0.0] * len(xs), [float(k) for k in range(len(xs))], gate("left"))
    assert counted.done == 0 and counted.times == ()
    assert counted.words() == "Laps: 0 through the gate (x = 0 from y = -1.4 to 0.2, crossed toward +x)."


@pytest.mark.parametrize(("args", "words"), [
    ((0.0, 0.2, -1.4, 1), "y_low must be below y_high"),
    ((float("nan"), -1.4, 0.2, 1), "finite numbers"),
    ((0.0, -1.4, 0.2, 2), r"sign must be \+1"),
    ((0.0, -1.4, 0.2, True), r"sign must be \+1"),
])
def test_a_gate_that_is_no_segment_is_refused(args, words):
    with pytest.raises(ValueError, match=words):
        Gate(*args)


class _Record:
    """What LapsDone reads of a simulator's StepRecord: the true pose after the step."""

    def __init__(self, x: float, y: float) -> None:
        self.pose = (x, y, 0.0)


class _LapsDoneFromFirstStep(LapsDone):
    """Wrong version kept: the count starts at the first step's position, not at the run's start, so a
    robot that starts on the gate and backs off first is given a lap it has not driven."""

    def __call__(self, record) -> bool:
        if not hasattr(self, "_seen"):
            self._seen = True
            self._last = (record.pose[0], record.pose[1])
            return False
        return super().__call__(record)


def _stop_index(rule: LapsDone, xs: list[float], ys: list[float]) -> int | None:
    """The row of the trace at which a run stopped by `rule` ends (row 0 is the start, never fed)."""
    for k in range(1, len(xs)):
        if rule(_Record(xs[k], ys[k])):
            return k
    return None


@pytest.mark.parametrize("shape", ["forward", "backed_off_first"])
def test_a_lap_run_stops_where_the_count_first_reaches_two(shape: str) -> None:
    """week6.laps_done ends a run at the step where the trace's own count first reaches LAPS, so the
    judgement of the shortened trace sees exactly the laps it was asked for, and not one step more."""
    xs, ys = circle(2.5)
    if shape == "backed_off_first":  # from the start on the gate back across it, then round
        xs, ys = [0.0, -0.01, 0.0] + xs[1:], [0.0, 0.0, 0.0] + ys[1:]
    g = Gate(0.0, -1.0, 0.05, 1)
    counted = laps(xs, ys, g)
    assert max(counted) >= 2
    assert _stop_index(LapsDone(g, 2, (xs[0], ys[0])), xs, ys) == counted.index(2)
    if shape == "backed_off_first":  # the wrong version stops a lap early: it never saw the step back
        wrong = _stop_index(_LapsDoneFromFirstStep(g, 2, (xs[0], ys[0])), xs, ys)
        assert wrong is not None and wrong < counted.index(2)


def test_week6_lap_runs_end_once_the_laps_are_done() -> None:
    """The solution's visible lap run ends at the step its second lap is done (the original test's break),
    well before the 90 s, and its trace counts exactly two laps."""
    from wrong_submissions import ROOT

    from grader.checks.week6 import LAPS, SECONDS
    from grader.grading import grade_submission

    traces: dict = {}
    result = grade_submission(6, ROOT / "solutions" / "week6", seed=2014, only="week6.laps.left",
                              traces=traces)
    check = next(c for c in result["checks"] if c["id"] == "week6.laps.left")
    steps = traces["week6.laps.left"]["steps"]
    counted = laps(steps["x"], steps["y"], gate("left"))
    assert check["status"] == "passed", check["message"]
    assert counted[-1] == LAPS and counted.index(LAPS) == len(counted) - 1
    assert steps["t"][-1] == check["details"]["t_laps"] < SECONDS - 20
    assert traces["week6.laps.left"]["ending"]["reason"] == "until"
