"""Week 3 checks: go-to-goal (theta_g, wrapped error, P, I, D, memory), ensure_w, and scenario runs.

Scenario metrics come from the simulator's true pose and the true goal, never from what the student's code
reports: reaching goals within d_stop in 30 s without a collision, and the course's settle time (<= 3 s)
and overshoot (<= 10 %) on the way to the goal (0, -1).
"""

from __future__ import annotations

import functools
import json
import math
import random
from pathlib import Path

from grader import reference as ref
from grader import scenarios
from grader.checks import Check, Context, Mismatch, Outcome
from grader.checks.answers import WILD, fmt, vector
from grader.checks.pid import PID_CHECKS
from grader.domains import Floats
from grader.margins import Limit, Margins
from grader.properties import run_property

SUPERVISOR = ("qb_supervisor.py",)
ALL = ("differential_drive.py", "quickbot.py", "go_to_angle.py", "go_to_goal.py", "qb_supervisor.py")
# The week's v, goal and d_stop (the course's arrival radius, judged on the TRUE position) and run length
# come from its declaration (simiam/course/weeks/week3.py, ctx.config).
GOAL_PLOTS = ("trajectory", "heading")  # the report: the path, and theta against theta_g with its band
ROBOT_D_STOP = 0.02  # the supervisor stops a little inside d_stop, so odometry drift cannot stop it outside
SETTLE_LIMIT = 3.0
TRACKING_TURN = (1.0, 2.2)  # rad: the hidden tracking goal's turn from the start, near the course's pi/2
EXCLUDED_FILE = Path(__file__).parent / "expected" / "week3_tracking_excluded.json"
OVERSHOOT_LIMIT = 0.10
SETTLE = Limit("settle time", "s", SETTLE_LIMIT, above=False)
OVERSHOOT = Limit("overshoot", "", OVERSHOOT_LIMIT, above=False, percent=True)  # a fraction of theta_g
REACH_HINT = (
    "Hint: the robot steers by your theta_g, the wrapped error and the PID terms (their own checks say which "
    "one is wrong), and ensure_w must keep w; replay the run in the report to see where it goes"
)
TUNE_HINT = (
    "Hint: first make theta_g, the wrapped error and the PID terms pass their own checks; then tune Kp, Ki, "
    "Kd in GoToGoal.__init__ (settle within 3 s, overshoot at most 10 %)"
)
OVERSHOOT_HINT = (
    "Hint: theta swings past theta_g (or away from it): first make theta_g, the wrapped error and the PID "
    "terms pass their own checks; then lower Kp or raise Kd in GoToGoal.__init__"
)


def _percent(ratio: float) -> str:
    """An overshoot as a percentage, or 'wildly off' where the figure would be absurd."""
    return f"{ratio:.1%}" if ratio <= WILD else f"wildly off: more than {WILD * 100:.0f} %"


def _ensure_w(ctx: Context, v: float, w: float) -> tuple[float, float]:
    answer = ctx.probe("ensure_w", v=v, w=w)
    vel_r, vel_l = vector(answer, 2, f"with v = {fmt(v)}, w = {fmt(w)} your ensure_w result")
    return vel_r, vel_l


_ensure_inputs = {"v": Floats(-0.5, 0.5), "w": Floats(-5.4, 5.4)}
_saturating = [{"v": 0.25, "w": 3.0}, {"v": -0.25, "w": -3.0}, {"v": 10.0, "w": 1.0}]


def keeps_w(ctx: Context) -> Outcome:
    def case(ctx: Context, v: float, w: float) -> None:
        spec = ctx.spec
        applied = ref.limit_speeds(*_ensure_w(ctx, v, w), spec.max_vel, spec.min_vel)
        got = ref.diff_to_uni(spec, *applied)[1]
        want = ref.ensure_w_command(spec, v, w)[1]
        if abs(got - want) > 1e-6 * max(1.0, abs(want)):
            raise Mismatch(
                f"with v = {fmt(v)}, w = {fmt(w)} the robot turned at w = {fmt(got)} after its motor "
                f"limits (max_vel = {fmt(spec.max_vel)} rad/s); ensure_w must keep w = {fmt(want)}"
            )

    return run_property(
        ctx,
        "week3.ensure_w.keeps_w",
        _ensure_inputs,
        case,
        examples=_saturating,
        passed="w is kept whenever the motors allow it",
    )


def within_max_vel(ctx: Context) -> Outcome:
    def case(ctx: Context, v: float, w: float) -> None:
        vel_r, vel_l = _ensure_w(ctx, v, w)
        top = ctx.spec.max_vel
        if max(abs(vel_r), abs(vel_l)) > top * (1 + 1e-9):
            raise Mismatch(
                f"with v = {fmt(v)}, w = {fmt(w)} your wheels were {fmt(vel_r)} and {fmt(vel_l)} rad/s; "
                f"neither may exceed max_vel = {fmt(top)}"
            )

    return run_property(
        ctx,
        "week3.ensure_w.max_vel",
        _ensure_inputs,
        case,
        examples=_saturating,
        passed="no wheel exceeds max_vel",
    )


def gives_up_v(ctx: Context) -> Outcome:
    def case(ctx: Context, v: float, w: float) -> None:
        spec = ctx.spec
        applied = ref.limit_speeds(*_ensure_w(ctx, v, w), spec.max_vel, spec.min_vel)
        got = ref.diff_to_uni(spec, *applied)[0]
        want = ref.ensure_w_command(spec, v, w)[0]  # the least v given up (a property, not a copy)
        if abs(got - want) > 1e-6 * max(1.0, abs(want)):
            raise Mismatch(
                f"with v = {fmt(v)}, w = {fmt(w)} the robot drove at v = {fmt(got)}, expected "
                f"{fmt(want)}: shift both wheels by the same amount, giving up only the v it must"
            )

    return run_property(
        ctx,
        "week3.ensure_w.gives_up_v",
        _ensure_inputs,
        case,
        examples=_saturating,
        passed="v is given up only as far as needed",
    )


def seeded_goals(
    seed: int, n: int, salt: str, turn: tuple[float, float] = (0.35, math.pi),
    excluded: frozenset[tuple[float, float]] = frozenset(),
) -> list[tuple[float, float]]:
    """Goals inside the week-3 arena, at least 0.5 m away, needing a turn in `turn` (rad) from the start,
    none of `excluded`.

    For settle and overshoot the turn is kept near the course's pi/2: a 10 % band around a small heading
    is narrower than one encoder tick of heading."""
    rng = random.Random(f"{seed}:{salt}")
    goals: list[tuple[float, float]] = []
    while len(goals) < n:
        g = (round(rng.uniform(-1.1, 1.1), 2), round(rng.uniform(-1.1, 1.1), 2))
        if drawable(g, turn) and g not in excluded:
            goals.append(g)
    return goals


def drawable(goal: tuple[float, float], turn: tuple[float, float]) -> bool:
    """At least 0.5 m away, a turn in `turn` (rad) from the start heading: a goal seeded_goals may give."""
    return math.hypot(*goal) >= 0.5 and turn[0] <= abs(ref.bearing(*goal)) <= turn[1]


# A run from a start away from the origin (issue 31): every other run starts at (0, 0, 0), where a theta_g
# that ignores the robot's position (atan2(y_g, x_g), a real student's) is right and collected every
# behaviour point. The start lies in START_BOX, at least START_MIN from the origin; the goal obeys the
# origin draws' rules (inside [-1.1, 1.1], at least 0.5 m and a turn of 0.35-pi rad from the start), and
# the line from the start along the origin's bearing to the goal passes MISS_BY or more from it, so that
# theta_g misses by a margin. tests/grader/test_week3_starts.py vets the draws as the other hidden draws
# are vetted: the reference solution and a correct alternative reach each with time and clearance to spare.
START_BOX = 0.6
START_MIN = 0.4
MISS_BY = 0.25


def seeded_start_and_goal(seed: int, salt: str) -> tuple[tuple[float, float, float], tuple[float, float]]:
    """A start pose away from the origin and a goal for it, drawn per seed (see START_BOX)."""
    rng = random.Random(f"{seed}:{salt}:away")
    while True:
        start = (round(rng.uniform(-START_BOX, START_BOX), 2), round(rng.uniform(-START_BOX, START_BOX), 2),
                 round(rng.uniform(-math.pi, math.pi), 2))
        goal = (round(rng.uniform(-1.1, 1.1), 2), round(rng.uniform(-1.1, 1.1), 2))
        if drawable_from(start, goal):
            return start, goal


def drawable_from(start: tuple[float, float, float], goal: tuple[float, float],
                  turn: tuple[float, float] = (0.35, math.pi)) -> bool:
    """A start and goal seeded_start_and_goal may give."""
    x0, y0, theta0 = start
    dx, dy = goal[0] - x0, goal[1] - y0
    if math.hypot(x0, y0) < START_MIN or math.hypot(dx, dy) < 0.5:
        return False
    if not turn[0] <= abs(ref.wrap(ref.bearing(dx, dy) - theta0)) <= turn[1]:
        return False
    b = ref.bearing(*goal)  # what a theta_g from the origin steers to, wherever the robot is
    ahead, beside = dx * math.cos(b) + dy * math.sin(b), abs(dy * math.cos(b) - dx * math.sin(b))
    return ahead < 0 or beside >= MISS_BY


@functools.cache
def tracking_excluded() -> frozenset[tuple[float, float]]:
    """Goals the tracking check never draws: a correct controller's settle time or overshoot there is within
    1 s or 3 points of the limit (instructor_tools/tracking_week3.py made the list; issue 20's rule that right
    and wrong are apart by a margin: without it one seed in about 130 failed the reference solution)."""
    data = json.loads(EXCLUDED_FILE.read_text(encoding="utf-8"))
    return frozenset((float(x), float(y)) for x, y in data["excluded"])


def _go(ctx: Context, check_id: str, goal: tuple[float, float],
        start: tuple[float, float, float] | None = None) -> scenarios.Run:
    week = ctx.config
    key = ("goal", goal, week.seconds, start)
    if key not in ctx.memo:
        settings = week.settings.with_changes(goal=list(goal), d_stop=ROBOT_D_STOP, state="go_to_goal")
        ctx.memo[key] = scenarios.run(
            ctx, f"goal ({goal[0]:g}, {goal[1]:g}){_from(start)}", settings.as_dict(), week.seconds,
            start=start, goal=goal, goal_radius=week.settings.d_stop, estimate_start=start,
        )
        scenarios.keep(ctx, check_id, ctx.memo[key])
    return ctx.memo[key]


def _from(start: tuple[float, float, float] | None) -> str:
    return "" if start is None else f" from ({start[0]:g}, {start[1]:g}) facing {start[2]:g} rad"


def _declared_goal(ctx: Context) -> tuple[float, float]:
    """The week's own goal (simiam/course/weeks/week3.py), the first goal of the visible runs."""
    goal = ctx.config.settings.goal
    if goal is None:
        raise ValueError(f"{ctx.config.name} declares no goal for its go-to-goal runs")
    return float(goal[0]), float(goal[1])


def reach_goals(hidden: bool):
    check_id = "week3.go_to_goal." + ("other_goals" if hidden else "reach_goals")

    def reach(ctx: Context) -> Outcome:
        # (goal, start): None starts at the world's (0, 0, 0); one run of each check starts elsewhere
        away = seeded_start_and_goal(ctx.seed, "hidden" if hidden else "visible")
        runs_to: list[tuple[tuple[float, float], tuple[float, float, float] | None]] = (
            [(g, None) for g in seeded_goals(ctx.seed, 2, "hidden")] + [(away[1], away[0])]
            if hidden
            else [(_declared_goal(ctx), None), ((0.0, -1.0), None), (away[1], away[0])]
        )
        if hidden and ctx.practice:
            practice = _practice(ctx, "other_goals")
            if not practice:
                return Outcome(0.0, _not_here(ctx), status="error")
            runs_to = [(_pair(v["goal"]), _pose(v["start"]) if "start" in v else None) for v in practice]
        reached, lines, runs, done, margins = 0, [], [], [], Margins()
        for goal, start in runs_to:
            r = _go(ctx, check_id, goal, start)
            done.append(r)
            scenarios.add_margins(margins, r, ctx.config.seconds)
            ok = r.reached and r.collision is None and not r.problem
            reached += ok
            where = f"({goal[0]:g}, {goal[1]:g}){_from(start)}"
            if ok:
                lines.append(f"{where} reached in {r.t_goal:.1f} s")
            else:
                why = r.problem or (
                    f"collided at t = {r.collision['t']:.2f} s"
                    if r.collision
                    else f"not reached in 30 s, {r.metrics['final_distance']:.2f} m away at the end"
                )
                lines.append(f"{where} {why}")
            runs.append({**r.metrics, "problem": r.problem, "start": list(start) if start else None})
        missed = reached < len(runs_to) and not any(r.problem for r in done)
        return Outcome(
            reached / len(runs_to),
            "; ".join(lines) + (f". {REACH_HINT}" if missed else ""),
            {"runs": runs, "traces": scenarios.trace_keys(done), "margins": margins.to_json()},
            status=scenarios.status_of(done),
        )

    reach.__name__ = "reach_" + ("other_goals" if hidden else "goals")
    return reach


def _tracking(ctx: Context, check_id: str, goal: tuple[float, float]) -> tuple[scenarios.Run, dict]:
    r = _go(ctx, check_id, goal)  # the reach run to the same goal, when there is one
    settle, overshoot = scenarios.settle_and_overshoot(r.trace, goal)
    margins = Margins()
    if not r.problem:
        margins.add(SETTLE, settle, r.label)
        margins.add(OVERSHOOT, overshoot, r.label)
    return r, {
        "goal": list(goal),
        "settle_time": settle,
        "overshoot": overshoot,
        **r.metrics,
        "measured_from": "true pose and true goal heading",
        "traces": scenarios.trace_keys([r]),
        "margins": margins.to_json(),
    }


def _only(m: dict, figure: str) -> dict:
    """The tracking figures with the margins of one figure (the settle check judges only the settle time)."""
    return {**m, "margins": [e for e in m["margins"] if e["figure"] == figure]}


def settle_time(ctx: Context) -> Outcome:
    r, m = _tracking(ctx, "week3.pid.settle_time", (0.0, -1.0))
    m = _only(m, SETTLE.figure)
    if r.problem:
        return Outcome(0.0, r.problem, m, status=scenarios.status_of([r]))
    if m["settle_time"] is None:
        return Outcome(0.0, f"theta never stayed within 10 % of theta_g (goal (0, -1)). {TUNE_HINT}", m)
    ok = m["settle_time"] <= SETTLE_LIMIT
    return Outcome(
        float(ok),
        f"theta settled within 10 % of theta_g after {m['settle_time']:.2f} s "
        f"(at most {SETTLE_LIMIT:g} s) on the way to (0, -1)" + ("" if ok else f". {TUNE_HINT}"),
        m,
    )


def overshoot(ctx: Context) -> Outcome:
    r, m = _tracking(ctx, "week3.pid.settle_time", (0.0, -1.0))
    m = _only(m, OVERSHOOT.figure)
    if r.problem:
        return Outcome(0.0, r.problem, m, status=scenarios.status_of([r]))
    ok = m["overshoot"] <= OVERSHOOT_LIMIT
    text = f"overshoot {_percent(m['overshoot'])} of theta_g (at most 10 %) on the way to (0, -1)"
    return Outcome(float(ok), text + ("" if ok else f". {OVERSHOOT_HINT}"), m)


def _practice(ctx: Context, check: str) -> list[dict]:
    """The practice variants of one hidden check (grade --practice): goals off the grid every seed draws
    from, so never a hidden goal (grader.practice, instructor_tools/practice_sets.py)."""
    from grader.practice import load_practice

    data = load_practice(3) if ctx.practice else None
    return [v for v in (data or {}).get("variants", []) if v.get("check") == check]


def _not_here(ctx: Context) -> str:
    from grader.practice import not_here

    return not_here(ctx)


def _pair(value: list) -> tuple[float, float]:
    return float(value[0]), float(value[1])


def _pose(value: list) -> tuple[float, float, float]:
    return float(value[0]), float(value[1]), float(value[2])


def tracking_other_goal(ctx: Context) -> Outcome:
    if ctx.practice:
        return _tracking_practice(ctx)
    goal = seeded_goals(ctx.seed, 1, "tracking", TRACKING_TURN, tracking_excluded())[0]
    r, m = _tracking(ctx, "week3.pid.tracking_other_goal", goal)
    if r.problem:
        return Outcome(0.0, r.problem, m, status=scenarios.status_of([r]))
    settle, over = m["settle_time"], m["overshoot"]
    ok = settle is not None and settle <= SETTLE_LIMIT and over <= OVERSHOOT_LIMIT
    text = "never settled" if settle is None else f"settled after {settle:.2f} s"
    text = f"goal ({goal[0]:g}, {goal[1]:g}): {text}, overshoot {_percent(over)}"
    return Outcome(float(ok), text + ("" if ok else f". {TUNE_HINT}"), m)


def _tracking_practice(ctx: Context) -> Outcome:
    """tracking_other_goal on every practice goal: its share of them met both limits."""
    goals = [_pair(v["goal"]) for v in _practice(ctx, "tracking_other_goal")]
    if not goals:
        return Outcome(0.0, _not_here(ctx), status="error")
    good, lines, runs, done, margins = 0, [], [], [], Margins()
    for goal in goals:
        r, m = _tracking(ctx, "week3.pid.tracking_other_goal", goal)
        done.append(r)
        if r.problem:
            lines.append(f"goal ({goal[0]:g}, {goal[1]:g}): {r.problem}")
            continue
        settle, over = m["settle_time"], m["overshoot"]
        margins.add(SETTLE, settle, r.label)
        margins.add(OVERSHOOT, over, r.label)
        ok = settle is not None and settle <= SETTLE_LIMIT and over <= OVERSHOOT_LIMIT
        good += ok
        text = "never settled" if settle is None else f"settled after {settle:.2f} s"
        lines.append(f"goal ({goal[0]:g}, {goal[1]:g}): {text}, overshoot {_percent(over)}")
        runs.append({k: v for k, v in m.items() if k != "margins"})
    text = "; ".join(lines) + ("" if good == len(goals) or any(r.problem for r in done) else f". {TUNE_HINT}")
    return Outcome(good / len(goals), text,
                   {"runs": runs, "traces": scenarios.trace_keys(done), "margins": margins.to_json()},
                   status=scenarios.status_of(done))


CHECKS = [
    *PID_CHECKS,
    Check("week3.ensure_w.keeps_w", "ensure_w keeps w", "property", 1.0, keeps_w, SUPERVISOR),
    Check(
        "week3.ensure_w.max_vel",
        "ensure_w never exceeds max_vel",
        "property",
        0.5,
        within_max_vel,
        SUPERVISOR,
    ),
    Check("week3.ensure_w.gives_up_v", "ensure_w gives up v, not w", "property", 0.5, gives_up_v, SUPERVISOR),
    Check(
        "week3.go_to_goal.reach_goals",
        "reach goals within d_stop in 30 s",
        "scenario",
        2.0,
        reach_goals(hidden=False),
        ALL,
        plots=GOAL_PLOTS,
    ),
    Check("week3.pid.settle_time", "settle time <= 3 s (goal (0, -1))", "scenario", 1.0, settle_time, ALL,
          plots=GOAL_PLOTS),
    Check("week3.pid.overshoot", "overshoot <= 10 % (goal (0, -1))", "scenario", 1.0, overshoot, ALL,
          plots=GOAL_PLOTS),
    Check(
        "week3.go_to_goal.other_goals",
        "reach goals drawn per seed",
        "scenario",
        1.5,
        reach_goals(hidden=True),
        ALL,
        visibility="hidden",
        plots=GOAL_PLOTS,
    ),
    Check(
        "week3.pid.tracking_other_goal",
        "settle and overshoot toward a goal drawn per seed",
        "scenario",
        1.0,
        tracking_other_goal,
        ALL,
        visibility="hidden",
        plots=GOAL_PLOTS,
    ),
]
