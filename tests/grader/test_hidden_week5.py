"""The instructor's hidden week-5 variants are fair: the reference solution completes every one as the
grader runs it (the world seen from the start pose, the grader's settings): the goal reached on the TRUE
pose, no collision, never closer to an obstacle than twice the limit the checks allow (MIN_CLEARANCE), and
(switching) well under the switch-rate limit."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from grader import scenarios
from grader.checks.week5 import D_STOP, MAX_RATE, MIN_CLEARANCE, setup
from grader.hidden import load_hidden
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.trace import EndReason

ROOT = Path(__file__).resolve().parents[2]


def test_hidden_set_is_present_and_big_enough() -> None:
    data = load_hidden(5)
    assert data is not None
    modes = [v["mode"] for v in data["variants"]]
    assert modes.count("blending") >= 10 and modes.count("switching") >= 10


def complete(folder: Path, variant: dict) -> str | None:
    """Why `folder`'s code fails the variant as the grader judges it, or None."""
    config = get_week(5)
    world, goal, settings, first, label = setup(config, variant["mode"], tuple(variant["goal"]),
                                                tuple(variant["start"]))
    sub = load_submission(folder, config)
    assert sub.ok, sub.errors
    sim = Simulator(world, LocalBrain(sub, config, settings), config.spec, dt=config.dt)
    trace = sim.run(config.seconds, until=lambda rec: math.dist(rec.pose[:2], goal) < D_STOP)
    if trace.collision is not None:
        return f"{label}: collided at t = {trace.collision['t']:.2f} s"
    if trace.ending is None or trace.ending.reason is not EndReason.UNTIL:
        return f"{label}: not reached in {config.seconds:g} s"
    gap = scenarios.min_clearance(trace, world, config.spec)
    if gap is not None and gap < 2 * MIN_CLEARANCE:
        return f"{label}: within {gap:.4f} m of an obstacle"
    names = [first, *trace.steps["state"][1:]]
    rate = sum(a != b for a, b in zip(names, names[1:], strict=False)) / trace.ending.t
    return f"{label}: {rate:.2f} switches per second" if rate > MAX_RATE / 2 else None


@pytest.mark.slow
def test_reference_solution_completes_every_hidden_variant() -> None:
    failed = [why for v in load_hidden(5)["variants"] if (why := complete(ROOT / "solutions/week5", v))]
    assert failed == []


def test_an_unfair_variant_is_refused() -> None:
    """The test can fail: straight from the start into the block below it."""
    assert complete(ROOT / "solutions/week5", {"mode": "blending", "start": [0, 0, -math.pi / 2],
                                               "goal": [0.5, -0.9]}) is not None


@pytest.mark.parametrize(("mistake", "check_id"), [
    ("week5_blend_only_goal", "week5.blending.hidden"),
    ("week5_switching_never_avoids", "week5.switching.hidden"),
])
def test_the_hidden_runs_catch_a_wrong_version(tmp_path, mistake, check_id) -> None:
    from wrong_submissions import build

    from grader.grading import grade_submission

    result = grade_submission(5, build(mistake, tmp_path), seed=2014, hidden=True, only=check_id)
    (check,) = result["checks"]
    assert check["status"] == "failed" and check["points"] < check["max_points"], check["message"]
    assert "collided" in check["message"]


def _former_seen_from(start, point):
    """The rotation week5.seen_from was written as when the hidden variants were validated (frozen here):
    the runs are only known fair for these very bits."""
    xs, ys, ts = start
    c, s = math.cos(-ts), math.sin(-ts)
    x, y = point
    return c * (x - xs) - s * (y - ys), s * (x - xs) + c * (y - ys)


def test_seen_from_is_the_inverse_of_the_simulators_placement() -> None:
    """The world seen from each hidden start, put back at the start by the simulator's own transform, is
    the week-5 world; and it is, bit for bit (signed zeros too), the world the variants were validated in."""
    from grader import reference as ref
    from grader.checks.week5 import seen_from
    from simiam.world import load_world

    world = load_world("week5")
    for v in load_hidden(5)["variants"]:
        start, goal = tuple(v["start"]), tuple(v["goal"])
        seen, goal_seen = seen_from(world, start, goal, "seen")
        for here, there in zip(seen.obstacles, world.obstacles, strict=True):
            back = ref.placed(start, here)
            assert max(math.dist(p, q) for p, q in zip(back, there, strict=True)) < 1e-12
            former = [_former_seen_from(start, p) for p in there]
            assert [tuple(map(float.hex, p)) for p in here] == [tuple(map(float.hex, p)) for p in former]
        assert tuple(map(float.hex, goal_seen)) == tuple(map(float.hex, _former_seen_from(start, goal)))
