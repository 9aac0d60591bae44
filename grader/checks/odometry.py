"""Week 2 odometry checks: the student's update_odometry along trusted tick sequences.

Each step is judged on its own, from the student's previous estimate and the tick differences, so every
correct odometry passes (the course's formula, the midpoint heading, the exact arc) and one mistake costs
one check: `heading` (theta changes by (d_r - d_l)/L), `distance` (the estimate moves (d_r + d_l)/2, or the
arc's chord), `direction` (it moves along a heading between the old and the new one). The paths are
straight lines, arcs, spins and reversing, driven by the trusted simulator, then random tick sequences.
`course_test` repeats the course's own test (25 steps of go-to-angle) and reports its relative errors; its
ticks and expected values are data precomputed by instructor tooling (grader/checks/expected/).
"""

from __future__ import annotations

import json
import math
from itertools import accumulate
from pathlib import Path

from grader import reference as ref
from grader.checks import Check, Context, Mismatch, Outcome
from grader.checks.answers import WILD, fmt, vector
from grader.domains import Floats, Integers, Lists, Row
from grader.properties import run_property

NEEDS = ("qb_supervisor.py",)
DT = 0.033
_TOL = 1e-6

_PATHS = {  # name: (wheel speeds in rad/s, steps)
    "straight": ((6.0, 6.0), 20),
    "arc to the left": ((8.0, 5.0), 25),
    "arc to the right": ((4.0, 7.0), 25),
    "spin to the left": ((-5.0, 5.0), 20),
    "spin to the right": ((5.0, -5.0), 20),
    "reversing": ((-6.0, -4.0), 15),
}


def _path_examples(ctx: Context) -> list[dict]:
    out = []
    for wheels, n in _PATHS.values():
        ticks, _ = ref.drive(ctx.spec, [wheels] * n, DT)
        prev = [(0, 0), *ticks[:-1]]
        out.append(
            {
                "steps": [[r - pr, lt - pl] for (r, lt), (pr, pl) in zip(ticks, prev, strict=False)],
                "start": [0.0, 0.0, 0.0],
            }
        )
    return out


_tick_steps = Lists(Row(Integers(-4, 4), Integers(-4, 4)), min_size=1, max_size=10)
_starts = Row(Floats(-1, 1), Floats(-1, 1), Floats(-math.pi, math.pi))


def _estimates(ctx: Context, steps: list, start: list) -> list[list[float]]:
    cumulative = [list(t) for t in accumulate(steps, lambda a, b: [a[0] + b[0], a[1] + b[1]])]
    answer = ctx.probe("odometry", ticks=cumulative, start=start)
    if not isinstance(answer, list) or len(answer) != len(steps):
        raise Mismatch("update_odometry did not leave an estimate after every step")
    return [vector(e, 3, f"after step {k + 1} your state_estimate") for k, e in enumerate(answer)]


def _between(angle: float, start: float, sweep: float) -> bool:
    """True if `angle` lies on the arc from `start` sweeping by `sweep` (either sign), within tolerance."""
    offset = ref.wrap(angle - start)
    lo, hi = (0.0, sweep) if sweep >= 0 else (sweep, 0.0)
    return lo - _TOL <= offset <= hi + _TOL


def _judge(aspect: str):
    def case(ctx: Context, steps: list, start: list) -> None:
        spec = ctx.spec
        prev = list(start)
        for k, (est, (d_right, d_left)) in enumerate(zip(_estimates(ctx, steps, start), steps, strict=False)):
            d_c, phi = ref.travel(spec, d_right, d_left)
            dx, dy, dtheta = est[0] - prev[0], est[1] - prev[1], est[2] - prev[2]
            moved = math.hypot(dx, dy)
            where = (
                f"at step {k + 1} (right wheel {d_right:+d} ticks, left {d_left:+d}) from "
                f"x = {fmt(prev[0])}, y = {fmt(prev[1])}, theta = {fmt(prev[2])}"
            )
            if aspect == "heading" and abs(ref.wrap(dtheta - phi)) > _TOL:
                raise Mismatch(
                    f"{where} your theta changed by {fmt(dtheta)}, expected (d_r - d_l)/L = {fmt(phi)}"
                )
            if aspect == "distance":
                chord = abs(d_c) * (math.sin(phi / 2) / (phi / 2) if phi else 1.0)
                if not chord - _TOL <= moved <= abs(d_c) + _TOL:
                    raise Mismatch(
                        f"{where} your estimate moved {fmt(moved)} m, expected (d_r + d_l)/2 = "
                        f"{fmt(abs(d_c))} m"
                    )
            if aspect == "direction" and abs(d_c) > 1e-9:
                if moved < 0.5 * abs(d_c):
                    raise Mismatch(f"{where} your estimate did not move (expected {fmt(abs(d_c))} m)")
                heading = math.atan2(math.copysign(1, d_c) * dy, math.copysign(1, d_c) * dx)
                if not _between(heading, prev[2], phi):
                    raise Mismatch(
                        f"{where} your estimate moved toward {fmt(heading)} rad; the robot faces "
                        f"{fmt(prev[2])} rad (x changes with cos(theta), y with sin(theta))"
                    )
            prev = est

    return case


def _property(aspect: str, passed: str):
    def run(ctx: Context) -> Outcome:
        return run_property(
            ctx,
            f"week2.odometry.{aspect}",
            {"steps": _tick_steps, "start": _starts},
            _judge(aspect),
            examples=_path_examples(ctx),
            max_examples=20,
            passed=passed,
        )

    run.__name__ = f"odometry_{aspect}"
    return run


EXPECTED = Path(__file__).resolve().parent / "expected" / "week2_odometry_course_test.json"


def _course_case() -> dict:
    """The course's test case with its expected values, precomputed by instructor tooling (python -m
    instructor_tools.expected): the grader ships to students and holds no odometry of its own."""
    return json.loads(EXPECTED.read_text())


def course_test(ctx: Context) -> Outcome:
    """The course's part-2 test: go-to-angle for 25 steps; relative errors of x, y, theta vs the true pose."""
    spec = ctx.spec
    case = _course_case()
    steps = case["tick_steps"]
    est = _estimates(ctx, steps, [0.0, 0.0, 0.0])[-1]
    reference, slack = list(case["estimate"]), 1e-9
    for d_r, d_l in steps:
        d_c, phi = ref.travel(spec, d_r, d_l)
        slack += abs(d_c * phi) / 2  # how far the midpoint or exact-arc variants may differ from the course's
    true = case["true_pose"]
    errors = [abs((t - e) / t) for t, e in zip(true, est, strict=True)]
    course = ", ".join(f"{n} {e:.3f}" if e <= WILD else f"{n} wildly off"
                       for n, e in zip(("x", "y", "theta"), errors, strict=True))
    off = math.dist(est[:2], reference[:2])
    details = {
        "relative_errors": errors,
        "true_pose": list(true),
        "estimate": est,
        "expected_estimate": reference,
        "allowed_position_difference": slack,
    }
    if off > slack or ref.angle_diff(est[2], reference[2]) > _TOL:
        mine = f"({fmt(est[0])}, {fmt(est[1])}, {fmt(est[2])})"
        want = f"({fmt(reference[0])}, {fmt(reference[1])}, {fmt(reference[2])})"
        return Outcome(
            0.0,
            f"after 25 steps of go-to-angle (v = 0.1, theta_d = pi/4) your estimate was "
            f"{mine}, "
            f"expected about {want}; relative errors to the true pose: {course}",
            details,
        )
    return Outcome(1.0, f"relative errors after 25 steps: {course} (the course's test)", details)


ODOMETRY_CHECKS = [
    Check(
        "week2.odometry.heading",
        "odometry: theta changes by (d_r - d_l)/L",
        "property",
        1.0,
        _property("heading", "theta follows the wheels"),
        NEEDS,
    ),
    Check(
        "week2.odometry.distance",
        "odometry: the estimate moves (d_r + d_l)/2",
        "property",
        1.0,
        _property("distance", "the estimate moves as far as the robot"),
        NEEDS,
    ),
    Check(
        "week2.odometry.direction",
        "odometry: the estimate moves along the heading",
        "property",
        1.0,
        _property("direction", "the estimate moves along theta"),
        NEEDS,
    ),
    Check(
        "week2.odometry.course_test",
        "odometry: the course's 25-step test",
        "property",
        0.5,
        course_test,
        NEEDS,
    ),
]
