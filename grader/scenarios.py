"""Scenario runs: the student's supervisor drives the robot in the trusted simulator; the grader measures.

The student's code runs in the worker behind a RemoteBrain and only ever returns wheel speeds (and debug
values that are only plotted). Every metric here is computed from the simulator's TRUE pose and the true
goal: time to goal, final distance, minimum clearance, collisions, the course's settle time and overshoot.
A run that the student's code breaks (an exception, a timeout, an invalid command) ends there and keeps
its trace so far.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from grader import clearance
from grader import reference as ref
from grader.checks import Context
from grader.margins import CLEARANCE, Limit, Margins
from grader.sandbox.errors import SandboxError, StudentTimeout
from grader.sandbox.same_core import SameCore
from simiam.signals import week_signals
from simiam.simulator import Simulator, StepRecord
from simiam.trace import EndReason, Trace
from simiam.world import World, load_world


@dataclass
class Run:
    """One scenario run: the trace (Seam 2) and how it ended."""

    label: str
    trace: Trace
    reached: bool = False
    t_goal: float | None = None
    problem: str = ""  # the student's code broke the run: why, in words
    sandbox_error: SandboxError | None = None
    metrics: dict[str, Any] = field(default_factory=dict)
    trace_key: str | None = None  # where keep() stored the trace (None: not kept)

    @property
    def collision(self) -> dict | None:
        return self.trace.collision

    @property
    def final_pose(self) -> tuple[float, float, float]:
        s = self.trace.steps
        return s["x"][-1], s["y"][-1], s["theta"][-1]


def _brain(ctx: Context, settings: dict[str, Any], session: Any = None, cpu: int | None = None,
           estimate: tuple[float, float, float] | None = None):
    from grader.sandbox.session import RemoteBrain

    return RemoteBrain(session if session is not None else ctx.session, settings, cpu=cpu, start=estimate)


def run(
    ctx: Context,
    label: str,
    settings: dict[str, Any],
    seconds: float,
    *,
    world: World | None = None,
    start: tuple[float, float, float] | None = None,
    goal: tuple[float, float] | None = None,
    goal_radius: float | None = None,
    session: Any = None,
    stop_rule: Callable[[tuple[float, float, float]], Callable[[StepRecord], bool]] | None = None,
    estimate_start: tuple[float, float, float] | None = None,
) -> Run:
    """Run the student's supervisor with `settings` for `seconds` (stop at a collision, or once the TRUE
    position is within `goal_radius` of `goal`, or once the check's own `stop_rule`, made from the run's
    TRUE start pose (nudged, as the trace's first row), is true of a step's record: week 6's laps).
    `session`: another worker than ctx.session (e.g. grader.earlier's, with the course's versions of
    earlier weeks' parts). `estimate_start`: where the supervisor's estimate starts, when not at the
    week's start (0, 0, 0): week 3's runs from elsewhere start it at their (un-nudged) start, as the robot
    is told."""
    config = ctx.config
    world = world or load_world(config.world)
    start = nudged(start or world.start, ctx.start_nudge)
    sim_goal = World(world.name, world.obstacles, [start], goal, world.source) if goal else world
    result = Run(
        label, Trace(week=ctx.week, dt=config.dt, world=world.to_json(), robot={}, start=list(start))
    )
    until = None if stop_rule is None else stop_rule(start)
    if goal is not None and goal_radius is not None:
        assert stop_rule is None, "a run stops at its goal or by its own rule, not both"

        def until(rec: StepRecord) -> bool:  # the TRUE position, never the student's estimate
            return math.dist(rec.pose[:2], goal) < goal_radius
    with SameCore() as cpu:  # the grader and the worker take turns: on one core (speed only)
        try:
            brain = _brain(ctx, settings, session, cpu, estimate_start)
            sim = Simulator(sim_goal, brain, ctx.spec, dt=config.dt, start=start,
                            signals=week_signals(config))
        except SandboxError as exc:
            result.problem, result.sandbox_error = _words(exc, 0.0), exc
            return result
        trace = sim.run(seconds, until=until, stuck=(StudentTimeout,))
    trace.meta = {"check_label": label, "seed": ctx.seed,
                  "numerics": getattr(ctx.session, "numerics", None)}  # what ran the student's code
    result.trace = trace
    ending = trace.ending
    assert ending is not None  # run() always says how it ended
    if ending.reason is EndReason.UNTIL:
        if goal is not None:  # else the check's own rule ended the run (its judgement reads the trace)
            result.reached, result.t_goal = True, ending.t
    elif ending.reason is EndReason.INVALID_COMMAND:
        result.problem = f"at t = {ending.t:.2f} s your supervisor gave an invalid command: {ending.message}"
    elif ending.broken and isinstance(ending.error, SandboxError):
        result.problem, result.sandbox_error = _words(ending.error, ending.t), ending.error
    elif ending.broken:  # RemoteBrain raises only the session's errors: anything else is the grader's bug
        raise ending.error or RuntimeError(ending.message)
    x, y, _ = result.final_pose
    result.metrics = {
        "seconds": trace.seconds,
        "collided": trace.collision is not None,
        "path_length": path_length(trace),
        "min_clearance": min_clearance(trace, world, ctx.spec),
    }
    if goal is not None:
        result.metrics.update(
            {
                "goal": list(goal),
                "reached": result.reached,
                "time_to_goal": result.t_goal,
                "final_distance": math.dist((x, y), goal),
            }
        )
    return result


def nudged(start: tuple[float, float, float], nudge: tuple[float, float]) -> tuple[float, float, float]:
    """`start` moved by the grading's start nudge (Context.start_nudge): unchanged (the same tuple) without
    one, so an ordinary grading's start pose is the declared one to the bit."""
    dx, dy = nudge
    if dx == 0.0 and dy == 0.0:
        return start
    x, y, theta = start
    return (x + dx, y + dy, theta)


def clearance_of(r: Run) -> float | None:
    """The run's smallest TRUE clearance to the obstacles: 0 when it collided, None without obstacles."""
    if r.collision is not None:
        return 0.0
    return r.metrics.get("min_clearance")


def arrival(seconds: float) -> Limit:
    """The limit on the arrival time of a run of `seconds` to a goal."""
    return Limit("arrival time", "s", seconds, above=False)


def add_margins(margins: Margins, r: Run, seconds: float | None = None, clearance: Limit = CLEARANCE) -> None:
    """The run's clearance (against `clearance`: by default more than 0, no collision) and, with `seconds`
    (a run to a goal), its arrival time against their limits. A run the student's code broke has no
    figures: its verdict is the error, not a distance to a limit."""
    if r.problem:
        return
    if clearance_of(r) is not None:
        margins.add(clearance, clearance_of(r), r.label)
    if seconds is not None:
        margins.add(arrival(seconds), r.t_goal if r.reached else None, r.label)


def _words(exc: SandboxError, t: float) -> str:
    from grader.checks import sandbox_message

    return f"at t = {t:.2f} s " + sandbox_message(exc)[1]


def path_length(trace: Trace) -> float:
    """Distance the robot really drove (true positions)."""
    xs, ys = trace.steps["x"], trace.steps["y"]
    return sum(math.hypot(xs[i + 1] - xs[i], ys[i + 1] - ys[i]) for i in range(len(xs) - 1))


def min_clearance(trace: Trace, world: World, spec, every: int = 1) -> float | None:
    """The smallest gap (m) between the robot's base plate and any obstacle, at every `every`-th step
    (and the last); 0 once they touch. None for a world without obstacles. Every step by default: it is
    the figure the collision margins are read from (grader.margins), and a step moves the robot up to
    7.5 mm, so sampling fewer steps could overstate a margin by more than that (about 20 ms a 90 s run).

    Only the steps that can hold the smallest gap are measured: each step's cheap lower bound
    (clearance.pose_bounds), nearest first, until the bound passes the smallest gap found. The minimum is
    the one every step measured would give, bit for bit (tests/grader/test_same_after_issue24.py)."""
    if not world.obstacles:
        return None
    obstacles = [clearance.Shape(p) for p in world.obstacles]
    plate = spec.base_plate
    s = trace.steps
    xs, ys, ths = s["x"], s["y"], s["theta"]
    rows = list(range(0, len(xs), every)) + [len(xs) - 1]
    poses = [(xs[k], ys[k], ths[k]) for k in rows]
    bounds = clearance.pose_bounds(plate, poses, obstacles)
    gap = math.inf

    def measure(pose: tuple[float, float, float]) -> None:
        nonlocal gap
        body = clearance.Shape(ref.placed(pose, plate))
        for obstacle in obstacles:
            if clearance.box_gap(body.box, obstacle.box) < gap:  # else it cannot be the nearest
                gap = clearance.nearer(body, obstacle, gap)

    # a pose that is not a number is bounded by -inf: measured, and left out by measure()'s box test as
    # before (a NaN bound, which pose_bounds never gives, would upset the sort: kept out)
    finite = [i for i, b in enumerate(bounds) if b == b]
    # the poses nearest first, while a bound is not beyond the gap so far: the gap falls fast, and once a
    # bound passes it (by more than any rounding) no later pose can be nearer
    for i in sorted(finite, key=bounds.__getitem__):
        if bounds[i] > gap + clearance.SLACK:
            break
        measure(poses[i])
    return gap


def max_displacement(trace: Trace) -> float:
    """How far from its start the robot ever got."""
    x0, y0 = trace.steps["x"][0], trace.steps["y"][0]
    return max(math.hypot(x - x0, y - y0) for x, y in zip(trace.steps["x"], trace.steps["y"], strict=False))


def settle_and_overshoot(trace: Trace, goal: tuple[float, float]) -> tuple[float | None, float]:
    """The course's part-3.2 measures, from the TRUE pose and the true goal heading.

    y = wrapped true heading, r = heading from the true position to the goal, one sample per step from t = 0.
    settle = (k - 20) dt with k the first index that ends 21 consecutive samples with |(r - y)/r| < 0.1
    (None if it never settles). overshoot = |r_i - y_i| / |r_i| at the sample where y goes furthest in the
    direction of r (min y for a goal heading below 0, as the course's goal (0, -1); max y otherwise).
    r - y is an angle difference and is wrapped into [-pi, pi] (the course's plot never crosses +-pi).
    """
    s = trace.steps
    dt = trace.dt
    y = [ref.wrap(th) for th in s["theta"]]
    r = [ref.bearing(goal[0] - px, goal[1] - py) for px, py in zip(s["x"], s["y"], strict=False)]
    run_length, settle = 0, None
    for k, (rk, yk) in enumerate(zip(r, y, strict=False)):
        run_length = run_length + 1 if rk != 0 and abs(ref.wrap(rk - yk) / rk) < 0.1 else 0
        if run_length == 21:
            settle = (k - 20) * dt
            break
    sign = -1.0 if r[0] < 0 else 1.0
    i = max(range(len(y)), key=lambda k: sign * y[k])
    # the difference of two angles is wrapped: a heading of -3.1 is 0.08 rad from a goal bearing of 3.1,
    # not 6.2 rad (unwrapped, a heading that never passed the bearing reported 178 % or 306 %)
    overshoot = abs(ref.wrap(r[i] - y[i])) / abs(r[i]) if r[i] != 0 else 1.0
    return settle, overshoot


def keep(ctx: Context, check_id: str, r: Run) -> None:
    """Store the run's trace for the report: the first under the check id, later ones as id#2, id#3..."""
    key, n = check_id, 1
    while key in ctx.traces:
        n += 1
        key = f"{check_id}#{n}"
    r.trace.meta["check"] = check_id
    ctx.traces[key] = r.trace.to_json()
    r.trace_key = key


def trace_keys(runs: list[Run]) -> list[str]:
    """The trace keys of these runs, for a check's details["traces"] (the report shows those)."""
    return [r.trace_key for r in runs if r.trace_key is not None]


def status_of(runs: list[Run]) -> str | None:
    """ "timeout" or "error" when a run ended because the worker timed out or died, else None (the
    check's status then follows its points)."""
    from grader.checks import sandbox_message
    from grader.sandbox.errors import StudentError

    for r in runs:
        if r.sandbox_error is not None and not isinstance(r.sandbox_error, StudentError):
            return sandbox_message(r.sandbox_error)[0]
    return None
