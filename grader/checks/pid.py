"""Week 3 go-to-goal checks: theta_g, the wrapped error, and the P, I and D terms each on its own.

Each check sets the gains so that only the term it checks is in w (Kp only, Ki only, Kd only), calls the
student's GoToGoal.execute on poses where the heading error needs no wrapping, and compares w with the
term computed from the student's own theta_g: one mistake costs one check. `memory` checks that E_k and
e_k_1 carry over between calls by comparing a sequence of calls with fresh controllers.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

from grader import reference as ref
from grader.checks import Check, Context, Mismatch, Outcome
from grader.checks.answers import fmt, number, vector
from grader.properties import run_property

NEEDS = ("go_to_goal.py",)
V = 0.2

_coord = st.floats(-1.0, 1.0)
# poses facing roughly +x and goals ahead of them: theta_g - theta stays inside (-pi, pi), no wrap needed
_facing = st.floats(-1.4, 1.4)
_ahead = st.floats(0.2, 2.0)
_side = st.floats(-2.0, 2.0)
_dts = st.sampled_from([0.01, 0.033, 0.05, 0.1])


def _calls(ctx: Context, gains: dict, poses: list, goals: list, dt: float, fresh: bool = False) -> list:
    calls = [{"pose": list(p), "goal": list(g), "v": V, "dt": dt} for p, g in zip(poses, goals, strict=True)]
    answer = ctx.probe("go_to_goal", gains=gains, calls=calls, fresh=fresh)
    if not isinstance(answer, list) or len(answer) != len(calls):
        raise Mismatch("GoToGoal.execute did not answer every call")
    out = []
    for call, a in zip(calls, answer, strict=True):
        where = _where(call["pose"], call["goal"])
        if not isinstance(a, dict):
            raise Mismatch(f"{where} GoToGoal.execute gave no answer")
        v, w = vector(a.get("out"), 2, f"{where} your GoToGoal.execute result")
        theta_g = a.get("theta_g")
        theta_g = number(theta_g, f"{where} your theta_g") if theta_g is not None else None
        out.append((v, w, theta_g))
    return out


def _where(pose: list, goal: list) -> str:
    x, y, th = pose
    at_goal = f"({fmt(goal[0])}, {fmt(goal[1])})"
    return f"with the robot at ({fmt(x)}, {fmt(y)}) facing {fmt(th)} rad and the goal at {at_goal}"


def _error(theta_g: float | None, pose: list, goal: list) -> float:
    """The wrapped heading error, from the student's theta_g when they gave one (isolates the checks)."""
    if theta_g is None:
        theta_g = ref.theta_g(pose[0], pose[1], *goal)
    return ref.wrap(theta_g - pose[2])


def _close(a: float, b: float) -> bool:
    return abs(a - b) <= 1e-6 * max(1.0, abs(b))


def theta_g(ctx: Context) -> Outcome:
    def case(ctx: Context, x: float, y: float, theta: float, x_g: float, y_g: float) -> None:
        ((_, _, got),) = _calls(ctx, {"Kp": 1, "Ki": 0, "Kd": 0}, [[x, y, theta]], [[x_g, y_g]], 0.033)
        expected = ref.theta_g(x, y, x_g, y_g)
        if got is None or ref.angle_diff(got, expected) > 1e-6:
            raise Mismatch(
                f"{_where([x, y, theta], [x_g, y_g])} your theta_g was "
                f"{'missing' if got is None else fmt(got)}, expected atan2(y_g - y, x_g - x) = "
                f"{fmt(expected)}"
            )

    quadrants = [
        {"x": 0.0, "y": 0.0, "theta": 0.0, "x_g": gx, "y_g": gy}
        for gx, gy in ((1, 1), (-1, 1), (-1, -1), (1, -1), (0, 1), (-1, 0))
    ]
    strategies = {
        "x": _coord,
        "y": _coord,
        "theta": st.floats(-math.pi, math.pi),
        "x_g": _coord,
        "y_g": _coord,
    }
    return run_property(
        ctx,
        "week3.go_to_goal.theta_g",
        strategies,
        case,
        examples=quadrants,
        passed="theta_g points at the goal in every quadrant",
    )


def error_wrap(ctx: Context) -> Outcome:
    def case(ctx: Context, theta: float, x_g: float, y_g: float) -> None:
        pose, goal = [0.0, 0.0, theta], [x_g, y_g]
        ((_, w, tg),) = _calls(ctx, {"Kp": 1, "Ki": 0, "Kd": 0}, [pose], [goal], 0.033)
        expected = _error(tg, pose, goal)
        if not _close(w, expected):
            raise Mismatch(
                f"{_where(pose, goal)} and Kp = 1 (Ki = Kd = 0) your w was {fmt(w)}, expected the "
                f"error wrapped into [-pi, pi]: {fmt(expected)}"
            )

    examples = [
        {"theta": th, "x_g": -1.0, "y_g": gy}
        for th, gy in ((-3.0, 0.1), (3.0, -0.1), (2 * math.pi, 0.5), (-4 * math.pi + 0.3, -0.5))
    ]
    strategies = {"theta": st.floats(-4 * math.pi, 4 * math.pi), "x_g": _coord, "y_g": _coord}
    return run_property(
        ctx,
        "week3.go_to_goal.error_wrap",
        strategies,
        case,
        examples=examples,
        passed="the error stays in [-pi, pi]",
    )


def _term(name: str, gain: str, expected_of):
    """A check of one PID term: only `gain` is non-zero, one call on a fresh controller."""

    def case(
        ctx: Context, x: float, y: float, theta: float, ahead: float, side: float, k: float, dt: float
    ) -> None:
        pose, goal = [x, y, theta], [x + ahead, y + side]
        gains = {"Kp": 0, "Ki": 0, "Kd": 0, gain: k}
        ((v, w, tg),) = _calls(ctx, gains, [pose], [goal], dt)
        e = _error(tg, pose, goal)
        expected = expected_of(e, k, dt)
        if not _close(w, expected):
            raise Mismatch(
                f"{_where(pose, goal)}, {gain} = {fmt(k)} (other gains 0) and dt = {fmt(dt)} your w "
                f"was {fmt(w)}, expected {fmt(expected)} ({name} of the error e_k = {fmt(e)})"
            )
        if not _close(v, V):
            raise Mismatch(f"{_where(pose, goal)} your v was {fmt(v)}, expected inputs.v = {V}")

    gains = st.floats(0.5, 10.0) if gain != "Kd" else st.floats(0.01, 1.0)
    strategies = {
        "x": _coord,
        "y": _coord,
        "theta": _facing,
        "ahead": _ahead,
        "side": _side,
        "k": gains,
        "dt": _dts,
    }

    def run(ctx: Context) -> Outcome:
        return run_property(ctx, f"week3.pid.{name}", strategies, case, passed=f"the {name} term is right")

    run.__name__ = f"pid_{name}"
    return run


def memory(ctx: Context) -> Outcome:
    """Three calls on one controller against three fresh ones: I must accumulate, D must difference."""

    def case(ctx: Context, thetas: list, dt: float) -> None:
        poses = [[0.0, 0.0, th] for th in thetas]
        goals = [[1.0, 0.3]] * len(poses)
        for gain, how in (("Ki", "accumulate"), ("Kd", "difference")):
            gains = {"Kp": 0, "Ki": 0, "Kd": 0, gain: 1.0}
            fresh = [w for _, w, _ in _calls(ctx, gains, poses, goals, dt, fresh=True)]
            kept = [w for _, w, _ in _calls(ctx, gains, poses, goals, dt)]
            if max(map(abs, fresh)) < 1e-12:
                raise Mismatch(
                    f"with only {gain} = 1 your w was always 0, so the controller keeps no memory "
                    f"to check (is the {'integral' if gain == 'Ki' else 'derivative'} term there?)"
                )
            for n in range(1, len(poses)):
                expected = sum(fresh[: n + 1]) if how == "accumulate" else fresh[n] - fresh[n - 1]
                if not _close(kept[n], expected):
                    word = "E_k, the error summed so far" if how == "accumulate" else "e_k_1, the last error"
                    raise Mismatch(
                        f"with only {gain} = 1, headings {', '.join(fmt(t) for t in thetas)} and "
                        f"dt = {fmt(dt)}, call {n + 1} on the same controller gave w = {fmt(kept[n])}, "
                        f"expected {fmt(expected)}: the term must use {word}"
                    )

    strategies = {"thetas": st.lists(_facing, min_size=3, max_size=3), "dt": _dts}
    return run_property(
        ctx,
        "week3.pid.memory",
        strategies,
        case,
        examples=[{"thetas": [0.0, 0.2, -0.3], "dt": 0.05}],
        max_examples=10,
        passed="E_k and e_k_1 carry over between calls",
    )


PID_CHECKS = [
    Check("week3.go_to_goal.theta_g", "theta_g: the heading to the goal", "property", 1.0, theta_g, NEEDS),
    Check(
        "week3.go_to_goal.error_wrap",
        "the heading error is wrapped into [-pi, pi]",
        "property",
        1.0,
        error_wrap,
        NEEDS,
    ),
    Check(
        "week3.pid.proportional",
        "PID: the proportional term",
        "property",
        0.5,
        _term("proportional", "Kp", lambda e, k, dt: k * e),
        NEEDS,
    ),
    Check(
        "week3.pid.integral",
        "PID: the integral term (with dt)",
        "property",
        0.5,
        _term("integral", "Ki", lambda e, k, dt: k * e * dt),
        NEEDS,
    ),
    Check(
        "week3.pid.derivative",
        "PID: the derivative term (with dt)",
        "property",
        0.5,
        _term("derivative", "Kd", lambda e, k, dt: k * e / dt),
        NEEDS,
    ),
    Check("week3.pid.memory", "PID: memory carried between calls", "property", 0.5, memory, NEEDS),
]
