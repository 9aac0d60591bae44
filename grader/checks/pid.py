"""Week 3 go-to-goal checks: theta_g, the wrapped error, and the P, I and D terms each on its own.

Each term check sets the gains so that only the term it checks is in w (Kp only, Ki only, Kd only), sets
the controller's memory (E_k, e_k_1) as earlier calls would have left it, calls the student's
GoToGoal.execute and compares w with the term computed from the student's own error e_k (which the provided
code keeps in e_k_1): one mistake costs one check, and a wrong wrap or theta_g is charged to its own check
only. The gains are pinned inside the worker, so an execute that overwrites them is still checked term by
term, and the overwrite is reported once, by `memory`: each call must follow from what the controller keeps
(E_k and e_k_1) and nothing else.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

from grader import reference as ref
from grader.checks import Check, Context, Mismatch, Outcome
from grader.checks.answers import fmt, number, vector
from grader.domains import Floats, Lists, SampledFrom
from grader.properties import run_property

NEEDS = ("go_to_goal.py",)
V = 0.2

_coord = Floats(-1.0, 1.0)
# poses facing roughly +x and goals ahead of them: theta_g - theta stays inside (-pi, pi), no wrap needed
_facing = Floats(-1.4, 1.4)
_ahead = Floats(0.2, 2.0)
_side = Floats(-2.0, 2.0)
_dts = SampledFrom([0.01, 0.033, 0.05, 0.1])
_memory = Floats(-1.0, 1.0)  # E_k and e_k_1 as earlier calls may have left them


class Answer(NamedTuple):
    """One GoToGoal.execute call as the student's code answered it (all validated numbers)."""

    v: float
    w: float
    theta_g: float | None
    e_k: float | None  # the error the controller kept for the next call (e_k_1 = e_k, provided code)
    E_k: float | None  # the integral it kept (E_k = e_I, provided code)
    overwrote: dict
    invalid: dict  # what theta_g, e_k or E_k was when not a finite number ("NaN"): only its check says so


def _calls(ctx: Context, gains: dict, poses: list, goals: list, dt: float, fresh: bool = False,
           memory: list | None = None) -> list[Answer]:
    calls: list[dict[str, Any]] = [
        {"pose": list(p), "goal": list(g), "v": V, "dt": dt} for p, g in zip(poses, goals, strict=True)
    ]
    for call, mem in zip(calls, memory or [], strict=False):
        if mem:
            call["memory"] = mem
    answer = ctx.probe("go_to_goal", gains=gains, calls=calls, fresh=fresh)
    if not isinstance(answer, list) or len(answer) != len(calls):
        raise Mismatch("GoToGoal.execute did not answer every call")
    out = []
    for call, a in zip(calls, answer, strict=True):
        where = _where(call["pose"], call["goal"])
        if not isinstance(a, dict):
            raise Mismatch(f"{where} GoToGoal.execute gave no answer")
        v, w = vector(a.get("out"), 2, f"{where} your GoToGoal.execute result")
        kept: dict[str, float | None] = {}
        invalid: dict[str, str] = {}
        for k in ("theta_g", "e_k", "E_k"):
            kept[k] = None
            if a.get(k) is not None:
                try:
                    kept[k] = number(a[k], f"{where} your {k}")
                except Mismatch as exc:  # charged by the check that reads this value, not by every one
                    invalid[k] = str(exc)
        overwrote = a.get("overwrote")
        gains_set = {k: x for k, x in overwrote.items() if k in ("Kp", "Ki", "Kd")} if isinstance(
            overwrote, dict) else {}
        out.append(Answer(v, w, kept["theta_g"], kept["e_k"], kept["E_k"], gains_set, invalid))
    return out


def _where(pose: list, goal: list) -> str:
    x, y, th = pose
    at_goal = f"({fmt(goal[0])}, {fmt(goal[1])})"
    return f"with the robot at ({fmt(x)}, {fmt(y)}) facing {fmt(th)} rad and the goal at {at_goal}"


def _student_error(a: Answer, pose: list, goal: list) -> float:
    """The heading error the student's code used (it keeps it in e_k_1 for the next call), so that a wrong
    wrap costs the wrap check only. Without one, the wrapped error from their theta_g (or the true one)."""
    if a.e_k is not None:
        return a.e_k
    theta_g = a.theta_g if a.theta_g is not None else ref.bearing(goal[0] - pose[0], goal[1] - pose[1])
    return ref.wrap(theta_g - pose[2])


def _close(a: float, b: float) -> bool:
    return abs(a - b) <= 1e-6 * max(1.0, abs(b))


def theta_g(ctx: Context) -> Outcome:
    def case(ctx: Context, x: float, y: float, theta: float, x_g: float, y_g: float) -> None:
        (a,) = _calls(ctx, {"Kp": 1, "Ki": 0, "Kd": 0}, [[x, y, theta]], [[x_g, y_g]], 0.033)
        if "theta_g" in a.invalid:
            raise Mismatch(a.invalid["theta_g"])
        # a property: theta_g is right when its unit vector points along the vector to the goal
        got = a.theta_g
        if got is None or ref.points_at(got, x_g - x, y_g - y) > 1e-6:
            off = "" if got is None else f", {fmt(ref.points_at(got, x_g - x, y_g - y))} rad off"
            u_x, u_y = x_g - x, y_g - y
            raise Mismatch(
                f"{_where([x, y, theta], [x_g, y_g])} your theta_g was "
                f"{'missing' if got is None else fmt(got)}{off}, expected {fmt(ref.bearing(u_x, u_y))}: it "
                "must point from the robot's position along the vector to the goal "
                f"({fmt(u_x)}, {fmt(u_y)}), math.atan2(u_y, u_x) = math.atan2({fmt(u_y)}, {fmt(u_x)})"
            )

    quadrants = [
        {"x": 0.0, "y": 0.0, "theta": 0.0, "x_g": gx, "y_g": gy}
        for gx, gy in ((1, 1), (-1, 1), (-1, -1), (1, -1), (0, 1), (-1, 0))
    ]
    # and one away from the origin: a theta_g that ignores the robot's position is right at (0, 0) only
    quadrants.append({"x": 0.5, "y": -0.5, "theta": 0.0, "x_g": -0.5, "y_g": 0.5})
    strategies = {
        "x": _coord,
        "y": _coord,
        "theta": Floats(-math.pi, math.pi),
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
        (a,) = _calls(ctx, {"Kp": 1, "Ki": 0, "Kd": 0}, [pose], [goal], 0.033)
        if "e_k" in a.invalid:
            raise Mismatch(a.invalid["e_k"])
        theta_g = a.theta_g if a.theta_g is not None else ref.bearing(x_g, y_g)
        expected = ref.wrap(theta_g - theta)
        got = a.e_k if a.e_k is not None else a.w  # with Kp = 1 alone, w is the error
        if not _close(got, expected):
            raise Mismatch(
                f"{_where(pose, goal)} your heading error e_k was {fmt(got)}, expected theta_g - theta = "
                f"{fmt(theta_g - theta)} wrapped into [-pi, pi]: {fmt(expected)} "
                "(atan2(sin(e), cos(e)) wraps any angle)"
            )

    examples = [
        {"theta": th, "x_g": -1.0, "y_g": gy}
        for th, gy in ((-3.0, 0.1), (3.0, -0.1), (2 * math.pi, 0.5), (-4 * math.pi + 0.3, -0.5))
    ]
    strategies = {"theta": Floats(-4 * math.pi, 4 * math.pi), "x_g": _coord, "y_g": _coord}
    return run_property(
        ctx,
        "week3.go_to_goal.error_wrap",
        strategies,
        case,
        examples=examples,
        passed="the error stays in [-pi, pi]",
    )


def _term(name: str, gain: str, expected_of, formula: str):
    """A check of one PID term: only `gain` is non-zero, one call on a fresh controller whose memory
    (E_k, e_k_1) is already set, as after earlier calls. The error is the student's own e_k, so a wrong
    theta_g or wrap costs their own checks, not this one."""

    def case(
        ctx: Context,
        x: float,
        y: float,
        theta: float,
        ahead: float,
        side: float,
        k: float,
        dt: float,
        E_k: float,
        e_k_1: float,
    ) -> None:
        pose, goal = [x, y, theta], [x + ahead, y + side]
        gains = {"Kp": 0, "Ki": 0, "Kd": 0, gain: k}
        (a,) = _calls(ctx, gains, [pose], [goal], dt, memory=[{"E_k": E_k, "e_k_1": e_k_1}])
        e = _student_error(a, pose, goal)
        true_error = ref.points_at(theta, ahead, side)  # how far the robot faces from the goal
        if abs(e) < 1e-12 and abs(true_error) > 1e-3:  # e.g. the stub's e_k = 0: nothing to check yet
            raise Mismatch(
                f"{_where(pose, goal)} your heading error e_k was 0 (the heading to the goal is "
                f"{fmt(true_error)} rad away), so the {name} term cannot be checked: fill in e_k first"
            )
        expected = expected_of(e, k, dt, E_k, e_k_1)
        if not _close(a.w, expected):
            raise Mismatch(
                f"{_where(pose, goal)}, {gain} = {fmt(k)} (other gains 0), dt = {fmt(dt)} and the memory "
                f"of earlier calls E_k = {fmt(E_k)}, e_k_1 = {fmt(e_k_1)}, your w was {fmt(a.w)}, expected "
                f"{formula} = {fmt(expected)} (with your error e_k = {fmt(e)})"
            )
        if not _close(a.v, V):
            raise Mismatch(f"{_where(pose, goal)} your v was {fmt(a.v)}, expected inputs.v = {V}")

    gains = Floats(0.5, 10.0) if gain != "Kd" else Floats(0.01, 1.0)
    strategies = {
        "x": _coord,
        "y": _coord,
        "theta": _facing,
        "ahead": _ahead,
        "side": _side,
        "k": gains,
        "dt": _dts,
        "E_k": _memory,
        "e_k_1": _memory,
    }
    example = {"x": 0.0, "y": 0.0, "theta": 0.0, "ahead": 1.0, "side": 0.5, "k": 1.0, "dt": 0.05,
               "E_k": 0.3, "e_k_1": -0.2}

    def run(ctx: Context) -> Outcome:
        return run_property(ctx, f"week3.pid.{name}", strategies, case, examples=[example],
                            passed=f"the {name} term is right")

    run.__name__ = f"pid_{name}"
    return run


def memory(ctx: Context) -> Outcome:
    """Three calls on one controller: each answer must follow from what the controller keeps (E_k and
    e_k_1, compared with a fresh controller given the same memory), and execute must leave the gains alone."""

    def case(ctx: Context, thetas: list, dt: float) -> None:
        poses = [[0.0, 0.0, th] for th in thetas]
        goals = [[1.0, 0.3]] * len(poses)
        gains = {"Kp": 0, "Ki": 1.0, "Kd": 1.0}
        kept = _calls(ctx, gains, poses, goals, dt)
        overwrote = {k: v for a in kept for k, v in a.overwrote.items()}
        if overwrote:
            words = ", ".join(f"{k} = {fmt(v) if isinstance(v, float) else v}" for k, v in overwrote.items())
            raise Mismatch(
                f"execute overwrote {'/'.join(overwrote)} ({words}): set the gains in __init__ (the gains "
                "block), so they can be tuned and checked; execute must only use them"
            )
        if max(abs(a.w) for a in kept) < 1e-12:
            raise Mismatch(
                "with Ki = Kd = 1 your w was always 0, so the controller keeps no memory to check "
                "(are the integral and derivative terms there?)"
            )
        carried: list[tuple[float, float]] = []  # (E_k, e_k_1) each call left for the next
        for a in kept[:-1]:
            bad = [a.invalid[k] for k in ("E_k", "e_k") if k in a.invalid]
            if bad:
                raise Mismatch(bad[0])
            if a.E_k is None or a.e_k is None:
                raise Mismatch("your controller kept no E_k or e_k_1 between calls")
            carried.append((a.E_k, a.e_k))
        memory = [None] + [{"E_k": e_sum, "e_k_1": e_last} for e_sum, e_last in carried]
        fresh = _calls(ctx, gains, poses, goals, dt, fresh=True, memory=memory)
        for n in range(1, len(poses)):
            if not _close(kept[n].w, fresh[n].w):
                e_sum, e_last = carried[n - 1]
                raise Mismatch(
                    f"with Ki = Kd = 1, headings {', '.join(fmt(t) for t in thetas)} and dt = {fmt(dt)}, "
                    f"call {n + 1} on the same controller gave w = {fmt(kept[n].w)}, but a new controller "
                    f"with the same E_k = {fmt(e_sum)} and e_k_1 = {fmt(e_last)} "
                    f"gave {fmt(fresh[n].w)}: keep what the next call needs in E_k and e_k_1 only"
                )

    strategies = {"thetas": Lists(_facing, min_size=3, max_size=3), "dt": _dts}
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
        _term("proportional", "Kp", lambda e, k, dt, E, e1: k * e, "Kp * e_k"),
        NEEDS,
    ),
    Check(
        "week3.pid.integral",
        "PID: the integral term (with dt)",
        "property",
        0.5,
        _term("integral", "Ki", lambda e, k, dt, E, e1: k * (E + e * dt), "Ki * (E_k + e_k * dt)"),
        NEEDS,
    ),
    Check(
        "week3.pid.derivative",
        "PID: the derivative term (with dt)",
        "property",
        0.5,
        _term("derivative", "Kd", lambda e, k, dt, E, e1: k * (e - e1) / dt, "Kd * (e_k - e_k_1) / dt"),
        NEEDS,
    ),
    Check("week3.pid.memory", "PID: memory carried between calls", "property", 0.5, memory, NEEDS),
]
