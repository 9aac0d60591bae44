"""Week 1 checks: the simulator runs headless with the week's code, and the robot stays still."""

from __future__ import annotations

import math

from grader import scenarios
from grader.checks import Check, Context, Outcome
from grader.margins import Limit, Margins

NEEDS = ("differential_drive.py", "quickbot.py", "qb_supervisor.py")
STILL = 1e-9  # m and rad: the robot must not move at all (no motion at all is exactly 0)
MOVED = Limit("distance moved", "m", STILL, above=False)
TURNED = Limit("heading turned", "rad", STILL, above=False)


def _run(ctx: Context) -> scenarios.Run:
    if "week1" not in ctx.memo:
        ctx.memo["week1"] = scenarios.run(ctx, "week 1 world", ctx.config.settings.as_dict(),
                                          ctx.config.seconds)
        scenarios.keep(ctx, "week1.run.headless", ctx.memo["week1"])
    return ctx.memo["week1"]


def headless(ctx: Context) -> Outcome:
    r = _run(ctx)
    if r.problem:
        return Outcome(0.0, r.problem, _details(r), status=scenarios.status_of([r]))
    return Outcome(1.0, f"the week-1 world ran for {r.trace.seconds:.1f} s without a problem", _details(r))


def _details(r: scenarios.Run) -> dict:
    return {**r.metrics, "traces": scenarios.trace_keys([r])}


def stays_still(ctx: Context) -> Outcome:
    r = _run(ctx)
    if r.problem:
        return Outcome(0.0, "the run did not finish: " + r.problem)
    x0, y0, th0 = r.trace.start
    x, y, th = r.final_pose
    moved = math.hypot(x - x0, y - y0)
    margins = Margins()
    margins.add(MOVED, moved, r.label)
    margins.add(TURNED, abs(th - th0), r.label)
    if moved > STILL or abs(th - th0) > STILL:
        return Outcome(
            0.0,
            f"the robot moved {moved:.3f} m and turned {abs(th - th0):.3f} rad; in week 1 it "
            "should stay still",
            {"moved": moved, "margins": margins.to_json()},
        )
    return Outcome(
        1.0,
        f"the robot stayed at its start pose for {r.trace.seconds:.1f} s",
        {"moved": moved, **_details(r), "margins": margins.to_json()},
    )


CHECKS = [
    Check("week1.run.headless", "the simulator runs the week-1 world", "scenario", 1.0, headless, NEEDS),
    Check("week1.run.stays_still", "the robot stays still", "scenario", 1.0, stays_still, NEEDS),
]
