"""Week 7 checks: the sliding test (sigma), progress toward the goal, the automaton's transitions probed on
synthetic events, and navigating out of the trap to the goal (the release goal, and hidden goals and start
headings drawn per seed, each one the reference solution reaches).

Two choices are accepted wherever the course allowed both (see assignments/week7/README.md):
- progress_made: the manual's "closer than d_prog - epsilon" (epsilon = 0.1) or the course author's
  "no farther than d_prog": a distance between d_prog - 0.1 and d_prog may count either way;
- the automaton: the author's (progress first, the wall's side from the IR sums) or the manual's (the
  side from the sliding tests): only transitions on which both agree are probed.
A singular sliding system (u_gtg and u_ao parallel, or u_gtg = 0 at the goal) must not stop the run; at the
goal (u_gtg = 0) the robot is not sliding. The navigation runs use the course's versions of the earlier
weeks' parts (grader.earlier), with the student's week-7 blocks in them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from grader import earlier, scenarios
from grader import reference as ref
from grader.checks import Check, Context, Mismatch, Outcome
from grader.checks.answers import fmt, number, vector
from grader.domains import Floats, Lists, SampledFrom
from grader.margins import Margins
from grader.properties import run_property
from simiam.world import World, load_world

SUPERVISOR = ("qb_supervisor.py",)
ALL = ("differential_drive.py", "quickbot.py", "go_to_angle.py", "go_to_goal.py", "avoid_obstacles.py",
       "ao_and_gtg.py", "follow_wall.py", "sliding_mode.py", "qb_supervisor.py")
D_GOAL = 0.05  # the course's test 7.1: the TRUE position within 0.05 m of the goal
EPSILON = 0.1  # the manual's slack in progress_made
# Closer than d_prog by less than this counts as progress only for a rule with no slack to speak of: less
# than the estimate moves on one encoder tick (2*pi*R/16 = 12.8 mm of a wheel, half that of the robot).
STALL_GAP = 0.005
HIDDEN_SECONDS = 60.0
NAVIGATE_HINT = (
    "Hint: replay the run in the report and follow the state timeline: the robot must follow the wall when "
    "it stops making progress at an obstacle, and leave it when it makes progress and no longer slides; "
    "if the property checks of sigma, progress and the transitions pass, tune d_at_obs and d_unsafe"
)

_component = Floats(-2.0, 2.0)
_vector = Lists(_component, min_size=2, max_size=2)
_coord = Floats(-1.4, 1.4)


# ------------------------------------------------------------------------------------------ sliding


def _sigma(ctx: Context, direction: str, u_gtg, u_ao, u_fw) -> tuple[bool, list[float] | None]:
    answer = ctx.probe("week7_sliding", direction=direction, u_gtg=list(u_gtg), u_ao=list(u_ao),
                       u_fw=list(u_fw))
    where = f"sliding_{direction} with u_gtg = {_v(u_gtg)}, u_ao = {_v(u_ao)}, u_fw = {_v(u_fw)}"
    if not isinstance(answer, dict) or not isinstance(answer.get("sliding"), bool):
        raise Mismatch(f"{where} did not return True or False")
    sigma = answer.get("sigma")
    if isinstance(sigma, list) and all(isinstance(c, list) and len(c) == 1 for c in sigma):
        sigma = [c[0] for c in sigma]  # a 2x1 column is fine too
    if isinstance(sigma, list) and len(sigma) == 2 and all(isinstance(c, str) for c in sigma):
        return answer["sliding"], None  # nan or inf from a singular system
    return answer["sliding"], vector(sigma, 2, f"{where} your sigma")


def _v(u) -> str:
    return f"({fmt(float(u[0]))}, {fmt(float(u[1]))})"


def sigma_solves(ctx: Context) -> Outcome:
    """[u_gtg u_ao] sigma = u_fw on well-conditioned systems, on both sides; sliding = both positive; and the
    singular systems (u_gtg = 0, u_ao parallel to u_gtg) do not stop the run, and at the goal (u_gtg = 0)
    the robot is not sliding."""

    def case(ctx: Context, direction: str, u_gtg: list, u_ao: list, u_fw: list) -> None:
        where = f"sliding_{direction} with u_gtg = {_v(u_gtg)}, u_ao = {_v(u_ao)}, u_fw = {_v(u_fw)}"
        sliding, sigma = _sigma(ctx, direction, u_gtg, u_ao, u_fw)  # an exception fails the case too
        if _det(u_gtg, u_ao) == 0.0:
            if u_gtg == [0.0, 0.0] and sliding:
                raise Mismatch(f"{where} (the estimate at the goal) returned True: with u_gtg = 0 no sigma "
                               "has both entries positive, so the robot is not sliding")
            return  # a singular system: any answer but an exception
        if sigma is None:
            raise Mismatch(f"{where}: your sigma was not two finite numbers")
        got = (u_gtg[0] * sigma[0] + u_ao[0] * sigma[1], u_gtg[1] * sigma[0] + u_ao[1] * sigma[1])
        scale = max(1.0, abs(u_fw[0]), abs(u_fw[1]))
        if max(abs(got[0] - u_fw[0]), abs(got[1] - u_fw[1])) > 1e-6 * scale:
            raise Mismatch(
                f"{where}: your sigma ({fmt(sigma[0])}, {fmt(sigma[1])}) gives sigma_1 * u_gtg + sigma_2 * "
                f"u_ao = {_v(got)}, not u_fw: {_sigma_slip(u_gtg, u_ao, u_fw, sigma)}"
            )
        want = sigma[0] > 0 and sigma[1] > 0
        if sliding != want:
            raise Mismatch(f"{where}: sigma = ({fmt(sigma[0])}, {fmt(sigma[1])}), so sliding is {want}, "
                           f"but the event returned {sliding}")

    def good(values: dict) -> bool:
        """Exactly singular (the examples), or far from it (a drawn system close to singular is skipped)."""
        g, a = values["u_gtg"], values["u_ao"]
        det = _det(g, a)
        return det == 0.0 or abs(det) > 0.05 * math.hypot(*g) * math.hypot(*a)

    examples = [
        {"direction": "left", "u_gtg": [1.0, 1.0], "u_ao": [-0.5, 0.3], "u_fw": [0.4, 1.2]},
        {"direction": "right", "u_gtg": [1.0, 1.0], "u_ao": [0.3, -0.5], "u_fw": [1.2, 0.4]},
        {"direction": "left", "u_gtg": [0.2, -1.0], "u_ao": [0.7, 0.1], "u_fw": [-0.3, 0.9]},
        # singular: at the goal, and u_ao parallel to u_gtg (both ways)
        {"direction": "left", "u_gtg": [0.0, 0.0], "u_ao": [0.3, -0.4], "u_fw": [0.8, 0.6]},
        {"direction": "right", "u_gtg": [0.0, 0.0], "u_ao": [0.3, -0.4], "u_fw": [0.8, 0.6]},
        {"direction": "left", "u_gtg": [0.5, 0.25], "u_ao": [1.0, 0.5], "u_fw": [0.75, 0.5]},
        {"direction": "right", "u_gtg": [0.5, 0.25], "u_ao": [-0.25, -0.125], "u_fw": [0.75, 0.5]},
    ]
    return run_property(
        ctx,
        "week7.sliding.sigma",
        {"direction": SampledFrom(["left", "right"]), "u_gtg": _vector, "u_ao": _vector, "u_fw": _vector},
        _guarded(case, good),
        examples=examples,
        max_examples=15,
        passed="sigma solves [u_gtg u_ao] sigma = u_fw, sliding is sigma_1 > 0 and sigma_2 > 0, and the "
               "singular systems (u_gtg = 0, u_ao parallel to u_gtg) do not stop the run",
    )


def _sigma_slip(u_gtg: list, u_ao: list, u_fw: list, sigma: Sequence[float]) -> str:
    """What a wrong sigma most likely got wrong: the matrix built by rows, a sign in Cramer's rule, or
    neither (issue 21: a sign slip was told to use u_gtg and u_ao as the columns)."""
    det = _det(u_gtg, u_ao)
    right = ((u_fw[0] * u_ao[1] - u_ao[0] * u_fw[1]) / det, (u_gtg[0] * u_fw[1] - u_fw[0] * u_gtg[1]) / det)
    rows = ((u_fw[0] * u_ao[1] - u_gtg[1] * u_fw[1]) / det, (u_gtg[0] * u_fw[1] - u_ao[0] * u_fw[0]) / det)

    def near(a: float, b: float) -> bool:
        return abs(a - b) <= 1e-6 * max(1.0, abs(b))

    columns = ("with u_gtg and u_ao as the COLUMNS of the matrix (np.column_stack, or np.linalg.solve(A, "
               "u_fw) with A = [[u_gtg_x, u_ao_x], [u_gtg_y, u_ao_y]])")
    if all(near(g, w) for g, w in zip(sigma, rows, strict=True)):
        return (f"your sigma solves the system with u_gtg and u_ao as the ROWS; solve [u_gtg u_ao] sigma = "
                f"u_fw {columns}")
    flipped = [i + 1 for i in range(2) if near(sigma[i], -right[i]) and not near(right[i], 0.0)]
    if flipped and all(near(abs(g), abs(w)) for g, w in zip(sigma, right, strict=True)):
        which = " and ".join(f"sigma_{i}" for i in flipped)
        return (f"{which} has the wrong sign, the right size: check the signs of Cramer's rule, sigma_1 = "
                "(u_fw_x u_ao_y - u_ao_x u_fw_y) / det, sigma_2 = (u_gtg_x u_fw_y - u_fw_x u_gtg_y) / det, "
                "det = u_gtg_x u_ao_y - u_ao_x u_gtg_y (or np.linalg.solve)")
    return f"solve [u_gtg u_ao] sigma = u_fw {columns}"


def _det(u_gtg: list, u_ao: list) -> float:
    return u_gtg[0] * u_ao[1] - u_ao[0] * u_gtg[1]


def _guarded(case, keep):
    """`case` run only on inputs `keep` accepts (the others pass: a drawn system too close to singular)."""

    def run(ctx: Context, **values) -> None:
        if keep(values):
            case(ctx, **values)

    return run


# ----------------------------------------------------------------------------------------- progress


def _distance_case(values: dict) -> tuple[list, list, float, float]:
    goal = [values["x_g"], values["y_g"]]
    angle = values["bearing"]
    distance = values["distance"]
    estimate = [goal[0] + distance * math.cos(angle), goal[1] + distance * math.sin(angle), 0.0]
    return goal, estimate, distance, values["d_prog"]


_PROGRESS = {"x_g": _coord, "y_g": _coord, "bearing": Floats(-math.pi, math.pi),
             "distance": Floats(0.0, 2.0), "d_prog": Floats(0.05, 2.5)}


def _stalled_step(ctx: Context, goal: list, distance: float, d_prog: float) -> None:
    """progress_made counted `distance`, a few millimetres closer than d_prog, as progress: then a step
    in which the estimate did not move (no encoder tick: it stays at d_prog) must count too. A strict `<`
    without slack says no there, and the automaton turns to the wall whenever the wheels' encoders miss a
    tick (hidden goals then end in a collision). The manual's slack (`< d_prog - 0.1`) never gets here.

    The estimate is put on the goal's x axis: its distance to the goal, |x_g - x|, is then the same last
    bit in every way of computing a length (norm, np.linalg.norm, math.hypot, sqrt of squares)."""
    estimate = [goal[0] + distance, goal[1], 0.0]
    at = abs(goal[0] - estimate[0])
    answer = ctx.probe("week7_progress", goal=goal, estimate=estimate, d_prog=at)
    made = answer.get("progress") if isinstance(answer, dict) else None
    if made is False:
        raise Mismatch(f"with the goal {_v(goal)}, progress_made returned True with the estimate "
                       f"{fmt(distance)} m from it and d_prog = {fmt(d_prog)} m, but False with d_prog = "
                       f"{fmt(at)} m, the estimate exactly that far (where a step with no encoder tick "
                       "leaves it after set_progress_point): with a strict < and no slack the automaton "
                       "turns to the wall whenever the wheels do not tick. Use <= (at least as close as "
                       "ever), or the manual's slack, < d_prog - 0.1")


def progress_made(ctx: Context) -> Outcome:
    def case(ctx: Context, **values) -> None:
        goal, estimate, distance, d_prog = _distance_case(values)
        answer = ctx.probe("week7_progress", goal=goal, estimate=estimate, d_prog=d_prog)
        where = (f"with the goal {_v(goal)}, the estimate {fmt(distance)} m from it and d_prog = "
                 f"{fmt(d_prog)} m")
        made = answer.get("progress") if isinstance(answer, dict) else None
        if not isinstance(made, bool):
            raise Mismatch(f"{where} progress_made did not return True or False")
        if distance < d_prog - EPSILON - 1e-9 and not made:
            raise Mismatch(f"{where} progress_made returned False: the robot is closer to the goal than "
                           "it has ever been (closer than d_prog - 0.1 even)")
        if distance > d_prog + 1e-9 and made:
            raise Mismatch(f"{where} progress_made returned True: the robot is farther from the goal than "
                           "d_prog, the closest it has been")
        if isinstance(answer.get("d_prog"), float) and answer["d_prog"] != d_prog:
            raise Mismatch(f"{where} progress_made changed d_prog to {fmt(answer['d_prog'])}: only "
                           "set_progress_point sets it")
        if made and d_prog - STALL_GAP <= distance < d_prog:
            _stalled_step(ctx, goal, distance, d_prog)

    examples = [
        {"x_g": 1.1, "y_g": 1.1, "bearing": 3.9, "distance": 0.5, "d_prog": 1.0},
        {"x_g": 1.1, "y_g": 1.1, "bearing": 3.9, "distance": 1.2, "d_prog": 1.0},
        {"x_g": -1.0, "y_g": 1.0, "bearing": 0.0, "distance": 0.0, "d_prog": 0.5},
        {"x_g": 1.0, "y_g": 1.0, "bearing": 0.0, "distance": 0.4975, "d_prog": 0.5},   # a step's move closer
    ]
    return run_property(ctx, "week7.progress.made", _PROGRESS, case, examples=examples, max_examples=15,
                        passed="progress_made compares the distance to the goal with d_prog")


def progress_point(ctx: Context) -> Outcome:
    def case(ctx: Context, **values) -> None:
        goal, estimate, distance, d_prog = _distance_case(values)
        answer = ctx.probe("week7_progress_point", goal=goal, estimate=estimate, d_prog=d_prog)
        where = (f"with the goal {_v(goal)}, the estimate {fmt(distance)} m from it and d_prog = "
                 f"{fmt(d_prog)} m,")
        got = number(answer.get("d_prog") if isinstance(answer, dict) else None,
                     f"{where} d_prog after set_progress_point")
        want = min(distance, d_prog)
        if abs(got - want) > 1e-9 * max(1.0, want):
            what = "the distance to the goal" if distance < d_prog else "d_prog unchanged (it was closer)"
            raise Mismatch(f"{where} set_progress_point left d_prog = {fmt(got)}, expected {fmt(want)}: "
                           f"{what}; d_prog is the smallest distance to the goal so far")

    examples = [
        {"x_g": 1.1, "y_g": 1.1, "bearing": 3.9, "distance": 0.5, "d_prog": 10.0},
        {"x_g": 1.1, "y_g": 1.1, "bearing": 0.3, "distance": 1.2, "d_prog": 1.0},
    ]
    return run_property(ctx, "week7.progress.point", _PROGRESS, case, examples=examples, max_examples=15,
                        passed="set_progress_point keeps the smallest distance to the goal")


# ---------------------------------------------------------------------------------------- automaton

# The situations probed: the state the robot is in, its fw_direction, the events that decide, and what
# every correct automaton does (the author's and the manual's alike). Events not named are drawn.
_NEAR_LEFT = [0.1, 0.12, 0.25, 0.3, 0.3]   # an obstacle on the left (sensors 1-2), nothing on the right
_NEAR_RIGHT = list(reversed(_NEAR_LEFT))
SITUATIONS = {
    "at_goal": ("go_to_goal", "", {"at_goal": True}, "stop",
                "at the goal (at_goal) the robot must stop"),
    "at_goal_on_wall": ("follow_wall", "left", {"at_goal": True}, "stop",
                        "at the goal (at_goal) the robot must stop, even while following a wall"),
    "unsafe": ("go_to_goal", "", {"at_goal": False, "unsafe": True}, "avoid_obstacles",
               "too close to an obstacle (unsafe) the robot must avoid it (avoid_obstacles)"),
    "unsafe_on_wall": ("follow_wall", "right", {"at_goal": False, "unsafe": True}, "avoid_obstacles",
                       "too close to an obstacle (unsafe) the robot must avoid it, even on a wall"),
    "free_progress": ("go_to_goal", "", {"at_goal": False, "unsafe": False, "at_obstacle": False,
                                         "progress_made": True, "obstacle_cleared": True},
                      "go_to_goal",
                      "with no obstacle near and progress made the robot keeps going to the goal"),
    "stuck_left": ("go_to_goal", "", {"at_goal": False, "unsafe": False, "at_obstacle": True,
                                      "obstacle_cleared": False, "progress_made": False,
                                      "sliding_left": True, "sliding_right": False},
                   "follow_wall/left", "at an obstacle on its left with no progress (and sliding_left) the "
                   "robot must follow the wall on the left"),
    "stuck_right": ("go_to_goal", "", {"at_goal": False, "unsafe": False, "at_obstacle": True,
                                       "obstacle_cleared": False, "progress_made": False,
                                       "sliding_left": False, "sliding_right": True},
                    "follow_wall/right", "at an obstacle on its right with no progress (and sliding_right) "
                    "the robot must follow the wall on the right"),
    "leave_left": ("follow_wall", "left", {"at_goal": False, "unsafe": False, "progress_made": True,
                                           "sliding_left": False, "sliding_right": True},
                   "go_to_goal", "following a wall on the left, with progress made and no longer sliding "
                   "left (sliding_left False; sliding_right does not matter), the robot must go to the goal"),
    "leave_right": ("follow_wall", "right", {"at_goal": False, "unsafe": False, "progress_made": True,
                                             "sliding_left": True, "sliding_right": False},
                    "go_to_goal", "following a wall on the right, with progress made and no longer sliding "
                    "right (sliding_right False), the robot must go to the goal"),
    "keep_sliding": ("follow_wall", "left", {"at_goal": False, "unsafe": False, "progress_made": True,
                                             "sliding_left": True, "sliding_right": False},
                     "follow_wall/left", "following a wall on the left and still sliding left "
                     "(sliding_left True) the robot must keep following it"),
    "no_progress_on_wall": ("follow_wall", "right", {"at_goal": False, "unsafe": False,
                                                     "progress_made": False},
                            "follow_wall/right", "following a wall with no progress made the robot must "
                            "keep following it"),
    "safe_again": ("avoid_obstacles", "", {"at_goal": False, "unsafe": False}, "not avoid_obstacles",
                   "once no longer unsafe the robot must leave avoid_obstacles"),
}
_EVENTS = ("at_goal", "at_obstacle", "unsafe", "obstacle_cleared", "progress_made", "sliding_left",
           "sliding_right")


def _step(ctx: Context, situation: str, drawn: list[bool]) -> tuple[dict, dict]:
    state, direction, fixed, _, _ = SITUATIONS[situation]
    events = {name: fixed.get(name, drawn[i]) for i, name in enumerate(_EVENTS)}
    # only what a robot can see at once (issue 21): unsafe is under d_unsafe < d_at_obs, so at_obstacle
    # too; obstacle_cleared is all five over d_at_obs, so exactly not at_obstacle. An automaton that asks
    # unsafe only inside its at_obstacle branch is the same automaton on the robot.
    if events["unsafe"]:
        events["at_obstacle"] = True
    events["obstacle_cleared"] = not events["at_obstacle"]
    distances = _NEAR_RIGHT if "right" in situation else _NEAR_LEFT
    answer = ctx.probe("week7_step", state=state, fw_direction=direction, events=events, distances=distances)
    if not isinstance(answer, dict):
        raise Mismatch("QBSupervisor.execute gave no answer")
    return events, answer


def transitions(ctx: Context) -> Outcome:
    def case(ctx: Context, situation: str, drawn: list) -> None:
        events, answer = _step(ctx, situation, drawn)
        state, direction, _, expected, words = SITUATIONS[situation]
        on = ", ".join(f"{k}={'True' if v else 'False'}" for k, v in events.items())
        distances = ", ".join(fmt(d) for d in (_NEAR_RIGHT if "right" in situation else _NEAR_LEFT))
        where = (f"in state {state}" + (f" (fw_direction {direction!r})" if direction else "")
                 + f" with {on} and the IR distances ({distances})")
        got = answer.get("state")
        shown = got if isinstance(got, str) else "no state"
        if expected == "not avoid_obstacles":
            if got == "avoid_obstacles":
                raise Mismatch(f"{where} your automaton stayed in avoid_obstacles: {words}")
            return
        want_state, _, want_side = expected.partition("/")
        if got != want_state:
            raise Mismatch(f"{where} your automaton switched to {shown}, expected {want_state}: {words}")
        if want_side:
            side, ran = answer.get("fw_direction"), answer.get("follow_wall_direction")
            if side != want_side:
                raise Mismatch(f"{where} your automaton set fw_direction to {side!r}, expected "
                               f"{want_side!r}: {words}")
            if ran != want_side:
                raise Mismatch(f"{where} FollowWall ran with inputs.direction = {ran!r}, not your "
                               f"fw_direction {side!r}: set self.fw_direction (the supervisor passes it "
                               "on after your block)")

    examples = [{"situation": name, "drawn": [False] * len(_EVENTS)} for name in SITUATIONS]
    return run_property(
        ctx,
        "week7.fsm.transitions",
        {"situation": SampledFrom(sorted(SITUATIONS)),
         "drawn": Lists(SampledFrom([False, True]), min_size=len(_EVENTS), max_size=len(_EVENTS))},
        case,
        examples=examples,
        max_examples=20,
        passed="every probed transition is right (stop, avoid, follow the wall on the right side, leave it)",
    )


# ---------------------------------------------------------------------------------------- scenarios


def turned(world: World, goal: tuple[float, float], turn: int, of: int) -> tuple[World, tuple[float, float]]:
    """The world and the goal rotated about the start by 2*pi*turn/of: the robot starts facing another way
    (its estimate still starts at (0, 0, 0), as the student's supervisor expects)."""
    about_start = (0.0, 0.0, 2 * math.pi * turn / of)
    moved = [ref.placed(about_start, [(x, y) for x, y in poly]) for poly in world.obstacles]
    label = f"trap world turned {360 * turn / of:g} degrees"
    return World(label, moved), ref.place(about_start, goal)


def navigate(ctx: Context, check_id: str, world: World, goal: tuple[float, float], label: str,
             seconds: float, margins: Margins) -> tuple[bool, str, dict, scenarios.Run]:
    """One run to `goal`: reached when the TRUE position comes within 0.05 m of it, with no collision."""
    settings = ctx.config.settings.with_changes(goal=tuple(goal)).as_dict()
    session, note = earlier.scenario_session(ctx)  # earlier weeks' parts: the course's versions
    r = scenarios.run(ctx, label, settings, seconds, world=world, goal=goal, goal_radius=D_GOAL,
                      session=session)
    scenarios.keep(ctx, check_id, r)
    scenarios.add_margins(margins, r, seconds)
    details = {**r.metrics, "problem": r.problem, "traces": scenarios.trace_keys([r])}
    where = f"goal ({goal[0]:.2f}, {goal[1]:.2f})" + (f" ({note})" if note else "")
    if r.problem:
        return False, f"{where}: {r.problem}", details, r
    if r.collision is not None:
        return False, f"{where}: collided at t = {r.collision['t']:.2f} s", details, r
    if not r.reached:
        return (False, f"{where}: not reached in {seconds:g} s ({r.metrics['final_distance']:.2f} m away at "
                       "the end)", details, r)
    return True, f"{where} reached in {r.t_goal:.1f} s without a collision", details, r


def navigate_hint(runs: list[scenarios.Run]) -> str:
    """The hint for runs that missed their goal. When d_prog never moved in a run, no threshold helps, so
    the general hint's "tune d_at_obs and d_unsafe" would send the student the wrong way (issue 21). What it
    says follows from the trace (issue 31): progress_made holding every time it was checked (d_prog never
    came down: no set_progress_point when progress is made) reads differently from progress_made failing
    after d_prog was set (its comparison never counts a step as progress again)."""
    for r in runs:
        kept = [d for d in r.trace.steps.get("d_prog", []) if type(d) in (int, float)]
        if len(kept) > 1 and all(d == kept[0] for d in kept):
            return stuck_progress_hint(kept[0], r.trace.steps.get("progress_made", []))
    return NAVIGATE_HINT


def stuck_progress_hint(d_prog: float, progress: list) -> str:
    """The hint for a run whose d_prog stayed at `d_prog`, from what progress_made returned each step
    (True, False, or None where it was not checked)."""
    held = sum(1 for p in progress if p is True)
    failed = sum(1 for p in progress if p is False)
    stayed = f"Hint: d_prog stayed at {fmt(d_prog)} m the whole run"
    if held + failed == 0:
        return (f"{stayed} and your automaton never checked progress_made: it must, in go_to_goal and "
                "follow_wall, to know when to follow the wall and when to leave it")
    if failed == 0:
        return (f"{stayed} and progress_made held all {held} times it was checked: d_prog never came down to "
                "the distance the robot reached, so progress_made always holds and the robot never turns to "
                "the wall (no tuning of d_at_obs or d_unsafe helps). Check that your automaton calls "
                "self.set_progress_point() when it makes progress, and set_progress_point's own check; the "
                "replay plots d_prog")
    return (f"{stayed}, and progress_made was False {failed} of the {held + failed} times it was "
            "checked: no step came closer to the goal than d_prog as your progress_made counts it, so "
            "nothing lowered d_prog (no tuning of d_at_obs or d_unsafe helps). Check progress_made's "
            "comparison (its own check: the estimate exactly at d_prog, a step with no encoder tick, is "
            "progress); the "
            "replay plots d_prog and progress_made")


def release_goal(ctx: Context) -> Outcome:
    goal = ctx.config.settings.goal or (1.1, 1.1)
    margins = Margins()
    ok, text, details, r = navigate(ctx, "week7.navigate.release_goal", load_world(ctx.config.world), goal,
                                    "the trap world", ctx.config.seconds, margins)
    hint = "" if ok or r.problem else f". {navigate_hint([r])}"
    return Outcome(float(ok), f"from inside the trap: {text}{hint}",
                   {**details, "margins": margins.to_json()}, status=scenarios.status_of([r]))


def other_goals(ctx: Context) -> Outcome:
    from grader.practice import not_here, variants_to_run

    # three different start headings (issue 21: seed 2014 once drew three variants turned 0 degrees)
    picks = variants_to_run(ctx, 7, lambda data: hidden_picks(data, ctx.seed))
    if not picks:
        return Outcome(0.0, not_here(ctx), status="error")
    good, lines, runs, done, margins = 0, [], [], [], Margins()
    for v in picks:
        world, goal = turned(load_world(ctx.config.world), tuple(v["goal"]), v["turn"], v["of"])
        ok, text, details, r = navigate(ctx, "week7.navigate.other_goals", world, goal, world.name,
                                        HIDDEN_SECONDS, margins)
        good += ok
        lines.append(f"{world.name}, {text}")
        runs.append({"variant": v, **details})
        done.append(r)
    missed = good < len(picks) and not any(r.problem for r in done)
    return Outcome(good / len(picks), "; ".join(lines) + (f". {navigate_hint(done)}" if missed else ""),
                   {"runs": runs, "traces": scenarios.trace_keys(done), "margins": margins.to_json()},
                   status=scenarios.status_of(done))


CHECKS = [
    Check("week7.sliding.sigma", "sigma solves [u_gtg u_ao] sigma = u_fw, also when singular", "property",
          1.0, sigma_solves, SUPERVISOR),
    Check("week7.progress.made", "progress_made compares the distance to the goal with d_prog", "property",
          1.0, progress_made, SUPERVISOR),
    Check("week7.progress.point", "set_progress_point keeps the closest distance to the goal", "property",
          0.5, progress_point, SUPERVISOR),
    Check("week7.fsm.transitions", "the automaton's transitions on synthetic events", "property", 2.0,
          transitions, ALL),
    Check("week7.navigate.release_goal", "out of the trap to the goal (1.1, 1.1) in 60 s, no collision",
          "scenario", 2.0, release_goal, ALL, plots=("trajectory", "states", "signals:d_prog,switches")),
    Check("week7.navigate.other_goals", "other goals and start headings drawn per seed", "scenario", 1.5,
          other_goals, ALL, visibility="hidden", plots=("trajectory", "states")),
]


def hidden_picks(data: dict, seed: int) -> list[dict]:
    """The hidden variants `seed` draws from the hidden set `data` (grader.hidden.identity records them)."""
    from grader.hidden.draw import draw, turn_quarter

    return draw(data["variants"], 3, f"{seed}:week7-variants",
                lambda v: (turn_quarter(v["turn"], v["of"]),))
