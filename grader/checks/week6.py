"""Week 6 checks: FollowWall's wall points and vectors (probed with chosen IR distances), the supervisor's
d_fw and fw_direction, and laps around the L-shaped obstacle on either side (hidden: other sides, start
headings and distances d_fw, each checked with the reference solution when the set was made).

The lap runs use the course's versions of the earlier weeks' parts (grader.earlier: odometry, IR distances,
the wheel speeds, AvoidObstacles' geometry), so a mistake there costs its own week, not this one.

Every check is a property, with no reference answer: the sensors by what the sensor left out measures, each
vector from the student's own earlier results (u_fw_tp from their u_fw_t, u_fw_p from their p_1 and p_2,
u_fw_pp from their u_fw_p, u_fw from their u_fw_tp and u_fw_pp), so one mistake costs its own check, not
every later one. The IR points are whatever the student's FollowWall keeps in ir_distances_wf (week 4's
geometry), so the sensor check does not depend on that week either.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from grader import earlier, scenarios
from grader.checks import Check, Context, Mismatch, Outcome
from grader.checks.answers import describe, fmt, number
from grader.domains import Floats, Lists, SampledFrom
from grader.laps import median_distance, turning_rate
from grader.margins import CLEARANCE, Limit, Margins
from grader.properties import run_property
from grader.sentences import then
from simiam.course.weeks import get_week
from simiam.laps import Gate, LapsDone, laps
from simiam.world import load_world

FW = ("follow_wall.py",)
SUPERVISOR = ("qb_supervisor.py",)
ALL = (
    "differential_drive.py",
    "quickbot.py",
    "go_to_angle.py",
    "go_to_goal.py",
    "avoid_obstacles.py",
    "ao_and_gtg.py",
    "follow_wall.py",
    "qb_supervisor.py",
)
V = 0.15  # the original test's speed
SECONDS = 90.0  # the original test's length
LAPS = 2  # the original test: back at the start twice and off again, and the run ends there
SETTLE = 10.0  # s: the distance to the wall is judged after the robot found the wall
DISTANCE_TOL = 0.05  # m: the median distance to the obstacle may differ this much from d_fw
# rad/s, the turning rate once the robot found the wall (grader.laps.turning_rate). Over every start heading,
# side and d_fw of 0.15, 0.18 and 0.2 m, under every BLAS kernel, the reference turns at most 0.59 rad/s and
# u_fw without its tangent (tests/data/wrong/week6_u_fw_no_tangent.patch) at least 2.46 rad/s: the cap sits
# near their geometric mean, a factor of 2 from either (issue 20: before it, that wrong version's verdict
# was whether it touched the wall, with 0 to 2 mm to spare, and flipped with the BLAS kernel).
MAX_TURNING = 1.2
IR_RANGE = (0.04, 0.3)
LAP_HINT = (
    "Hint: the checks of p_1/p_2, u_fw_tp, u_fw_p, u_fw_pp and u_fw say which part is wrong; if they all "
    "pass, try d_fw between 0.15 and 0.2 m (replay the run in the report)"
)

_distance = Floats(*IR_RANGE)
_coord = Floats(-1.0, 1.0)
_angle = Floats(-math.pi, math.pi)
_direction = SampledFrom(["left", "right"])
_d_fw = Floats(0.1, 0.25)
LEFT, RIGHT = (0, 1, 2), (4, 3, 2)


def gate(direction: str) -> Gate:
    """The week's lap gate (`WEEK.lap_gate`, crossed toward +x when following the wall on the left), the
    other way round on the right."""
    declared = get_week(6).lap_gate
    assert declared is not None, "week 6 declares its lap gate (simiam/course/weeks/week6.py)"
    return declared.reversed() if direction == "right" else declared


def _choice_problem(distances: list[float], direction: str, got: list[int]) -> str | None:
    """What is wrong with the sensors (i_1, i_2) chosen for p_1 and p_2, or None. The rule, as properties:
    both are candidates of the side (0, 1, 2 for the left, 4, 3, 2 for the right); the candidate left out
    measures no less than either (on a tie it comes later in that order: the original's stable sort, and
    the tie decides which "phantom wall" the robot follows when it sees nothing); p_1 -> p_2 runs the way
    the robot drives (left: the lower index first; right: the higher)."""
    side = RIGHT if direction == "right" else LEFT
    i_1, i_2 = got
    if i_1 == i_2 or i_1 not in side or i_2 not in side:
        return f"two different sensors of {', '.join(map(str, side))} ({direction} side)"
    (left_out,) = [k for k in side if k not in got]
    for k in sorted(got, key=lambda k: (-distances[k], -side.index(k))):   # the one to drop first
        if distances[left_out] < distances[k] or (
            distances[left_out] == distances[k] and side.index(left_out) < side.index(k)
        ):
            # say which one was left out: "sensor 3 ..., sensor 2 ..." read as if {3, 2} were expected
            closer = "as close as" if distances[left_out] == distances[k] else "closer than"
            return (
                f"the two closest of {', '.join(map(str, side))} (on a tie the first in that order): you "
                f"left out sensor {left_out}, which measures {fmt(distances[left_out])} m, {closer} sensor "
                f"{k} ({fmt(distances[k])} m) that you took"
            )
    if (i_1 < i_2) != (direction != "right"):
        return (
            "p_1 the higher index and p_2 the lower (the right side)"
            if direction == "right"
            else "p_1 the lower index and p_2 the higher (the left side)"
        ) + ", so p_2 - p_1 points forward"
    return None


def _pair(value: Any, what: str) -> tuple[float, float]:
    """A 2-vector from a student answer: [x, y], a column [[x], [y]], or (x, y, 1) taken from the 3x5
    homogeneous points (only x and y count)."""
    if isinstance(value, list) and all(isinstance(v, list) and len(v) == 1 for v in value):
        value = [v[0] for v in value]
    if not isinstance(value, list) or len(value) not in (2, 3):
        raise Mismatch(f"{what} was {describe(value)}, expected a vector (x, y)")
    return number(value[0], f"{what} (x)"), number(value[1], f"{what} (y)")


def _words(distances: list[float], pose: list[float], direction: str, d_fw: float | None = None) -> str:
    text = (
        f"with direction {direction!r}, IR distances {', '.join(fmt(d) for d in distances)} and the robot "
        f"at ({fmt(pose[0])}, {fmt(pose[1])}, {fmt(pose[2])})"
    )
    return text + (f", d_fw = {fmt(d_fw)}" if d_fw is not None else "")


def _follow_once(ctx: Context, distances: list, pose: list, direction: str, d_fw: float) -> dict:
    answer = ctx.probe("follow_wall", distances=distances, pose=pose, direction=direction, d_fw=d_fw, v=V)
    if not isinstance(answer, dict):
        raise Mismatch("FollowWall.execute gave no answer")
    return answer


def _points(answer: dict, where: str) -> list[tuple[float, float]]:
    wf = answer.get("ir_distances_wf")
    if not (
        isinstance(wf, list) and len(wf) >= 2 and all(isinstance(r, list) and len(r) == 5 for r in wf[:2])
    ):
        raise Mismatch(f"{where} the IR points ir_distances_wf were {describe(wf)}, expected 3x5")
    return [(number(wf[0][i], "ir_distances_wf"), number(wf[1][i], "ir_distances_wf")) for i in range(5)]


def _which(point: tuple[float, float], points: list[tuple[float, float]]) -> int | None:
    for i, q in enumerate(points):
        if math.dist(point, q) < 1e-9:
            return i
    return None


def sensors(ctx: Context) -> Outcome:
    """p_1 and p_2 are the IR points of the two closest sensors on the chosen side, in driving order."""

    def case(ctx: Context, distances: list, theta: float, direction: str) -> None:
        pose = [0.2, -0.3, theta]
        answer = _follow_once(ctx, distances, pose, direction, 0.15)
        where = _words(distances, pose, direction)
        points = _points(answer, where)
        got = []
        for name in ("p_1", "p_2"):
            p = _pair(answer.get(name), f"{where} your {name}")
            i = _which(p, points)
            if i is None:
                raise Mismatch(
                    f"{where} your {name} ({fmt(p[0])}, {fmt(p[1])}) is none of the five IR "
                    "points: take a column of ir_distances_wf (its x and y)"
                )
            got.append(i)
        problem = _choice_problem(distances, direction, got)
        if problem:
            raise Mismatch(
                f"{where} p_1 and p_2 were the points of sensors {got[0]} and {got[1]} (0..4), "
                f"expected {problem}"
            )

    examples = [
        {"distances": [0.1, 0.15, 0.3, 0.3, 0.3], "theta": 0.0, "direction": "left"},
        {"distances": [0.3, 0.3, 0.3, 0.15, 0.1], "theta": 0.0, "direction": "right"},
        {"distances": [0.3, 0.3, 0.2, 0.12, 0.25], "theta": 1.0, "direction": "right"},
        {"distances": [0.25, 0.12, 0.2, 0.3, 0.3], "theta": -2.0, "direction": "left"},
        {"distances": [0.1, 0.1, 0.1, 0.1, 0.1], "theta": 0.5, "direction": "right"},
    ]
    return run_property(
        ctx,
        "week6.follow_wall.sensors",
        {"distances": Lists(_distance, min_size=5, max_size=5), "theta": _angle, "direction": _direction},
        case,
        examples=examples,
        passed="p_1 and p_2 are the two closest IR points on the chosen side, in driving order",
    )


def _vectors_check(check_id: str, judge, passed: str):
    """A property over FollowWall's vectors: `judge(answer)` raises Mismatch. Each judges its vector from the
    student's own earlier ones (p_1 and p_2, u_fw_t, u_fw_p), so one mistake costs one check."""

    def case(
        ctx: Context, distances: list, x: float, y: float, theta: float, direction: str, d_fw: float
    ) -> None:
        pose = [x, y, theta]
        answer = _follow_once(ctx, distances, pose, direction, d_fw)
        judge(_Answer(answer, _words(distances, pose, direction, d_fw), pose, d_fw))

    examples = [
        {
            "distances": [0.1, 0.15, 0.3, 0.3, 0.3],
            "x": 0.0,
            "y": 0.0,
            "theta": 0.0,
            "direction": "left",
            "d_fw": 0.15,
        },
        {
            "distances": [0.3, 0.3, 0.3, 0.2, 0.12],
            "x": 0.5,
            "y": -0.5,
            "theta": 2.0,
            "direction": "right",
            "d_fw": 0.18,
        },
    ]

    def run(ctx: Context) -> Outcome:
        return run_property(
            ctx,
            check_id,
            {
                "distances": Lists(_distance, min_size=5, max_size=5),
                "x": _coord,
                "y": _coord,
                "theta": _angle,
                "direction": _direction,
                "d_fw": _d_fw,
            },
            case,
            examples=examples,
            passed=passed,
        )

    run.__name__ = check_id.rsplit(".", 1)[-1]
    return run


def _v(a: tuple[float, float]) -> str:
    return f"({fmt(a[0])}, {fmt(a[1])})"


def _dot(a: tuple[float, float], b: tuple[float, float]) -> float:
    return a[0] * b[0] + a[1] * b[1]


def _cross(a: tuple[float, float], b: tuple[float, float]) -> float:
    return a[0] * b[1] - a[1] * b[0]


def _length(a: tuple[float, float]) -> float:
    return math.hypot(a[0], a[1])


TOL = 1e-6  # m (all vectors here are a few decimetres long)


class _Answer:
    """One FollowWall answer read as 2-vectors, with where it came from for the messages."""

    def __init__(self, answer: dict, where: str, pose: list, d_fw: float) -> None:
        self.answer, self.where, self.d_fw = answer, where, d_fw
        self.robot = (pose[0], pose[1])

    def __getitem__(self, name: str) -> tuple[float, float]:
        return _pair(self.answer.get(name), f"{self.where} your {name}")


def _tangent(a: _Answer) -> None:
    """u_fw_t = p_2 - p_1; u_fw_tp is a unit vector pointing the same way."""
    p_1, p_2, t, tp = a["p_1"], a["p_2"], a["u_fw_t"], a["u_fw_tp"]
    if _length((p_2[0] - p_1[0], p_2[1] - p_1[1])) <= 1e-9:
        raise Mismatch(
            f"{a.where} your p_1 and p_2 were the same point {_v(p_1)}: two different IR points "
            "are needed to tell the wall's direction"
        )
    if _length((t[0] - (p_2[0] - p_1[0]), t[1] - (p_2[1] - p_1[1]))) > TOL:
        raise Mismatch(
            f"{a.where} your u_fw_t was {_v(t)} with p_1 = {_v(p_1)} and p_2 = {_v(p_2)}: expected "
            "p_2 - p_1, the vector along the wall"
        )
    if abs(_length(tp) - 1) > TOL:
        raise Mismatch(
            f"{a.where} your u_fw_tp was {_v(tp)}, of length {fmt(_length(tp))}: expected a unit "
            "vector, u_fw_t divided by its length"
        )
    if abs(_cross(tp, t)) > TOL * _length(t) or _dot(tp, t) <= 0:
        raise Mismatch(
            f"{a.where} your u_fw_tp {_v(tp)} does not point the way of your u_fw_t {_v(t)}: "
            "expected u_fw_t divided by its length"
        )


def _perpendicular(a: _Answer) -> None:
    """u_fw_p is perpendicular to the wall (the line through p_1 and p_2) and ends on it: from the robot to
    the nearest point of the wall, as long as the distance to it."""
    p_1, p_2, p = a["p_1"], a["p_2"], a["u_fw_p"]
    wall = (p_2[0] - p_1[0], p_2[1] - p_1[1])
    if _length(wall) <= 1e-9:
        raise Mismatch(
            f"{a.where} your p_1 and p_2 were the same point {_v(p_1)}: there is no wall line for "
            "u_fw_p to be perpendicular to"
        )
    unit = (wall[0] / _length(wall), wall[1] / _length(wall))
    if _follows_own_tangent(a, p_1, p):
        return
    end = (a.robot[0] + p[0], a.robot[1] + p[1])
    distance = abs(_cross((p_1[0] - a.robot[0], p_1[1] - a.robot[1]), unit))
    if abs(_dot(p, unit)) > TOL:
        raise Mismatch(
            f"{a.where} your u_fw_p {_v(p)} is not perpendicular to the wall through p_1 {_v(p_1)} "
            f"and p_2 {_v(p_2)} (its part along the wall is {fmt(_dot(p, unit))} m): expected "
            "(u_a - u_p) - ((u_a - u_p) . u_fw_tp) u_fw_tp, with u_a = p_1 and u_p = (x, y)"
        )
    to_wall = (p_1[0] - a.robot[0], p_1[1] - a.robot[1])
    if abs(_cross((end[0] - p_1[0], end[1] - p_1[1]), unit)) > TOL and _dot(p, to_wall) < 0 \
            and abs(_length(p) - distance) <= TOL:
        # the right length the wrong way (u_p - u_a): say so, not only that it misses the wall (issue 21)
        raise Mismatch(
            f"{a.where} your u_fw_p was {_v(p)}: the right length ({fmt(distance)} m) but pointing away "
            "from the wall, from the wall to the robot: expected (u_a - u_p) - ((u_a - u_p) . u_fw_tp) "
            "u_fw_tp, from the robot (u_p) to the wall (u_a = p_1)"
        )
    if abs(_cross((end[0] - p_1[0], end[1] - p_1[1]), unit)) > TOL:
        raise Mismatch(
            f"{a.where} your u_fw_p was {_v(p)} (length {fmt(_length(p))}): from the robot it does "
            f"not reach the wall through p_1 and p_2, which is {fmt(distance)} m away: expected the "
            "vector from the robot to the nearest point of the wall"
        )


def _follows_own_tangent(a: _Answer, p_1: tuple[float, float], p: tuple[float, float]) -> bool:
    """u_fw_p as the student's own u_fw_tp gives it, when that one is not a unit vector (its own check
    fails): the projection formula applied to it, so that a wrong u_fw_tp costs only its own check."""
    tp = a["u_fw_tp"]
    if abs(_length(tp) - 1) <= TOL or _length(tp) <= 1e-9:
        return False
    to_wall = (p_1[0] - a.robot[0], p_1[1] - a.robot[1])
    along = _dot(to_wall, tp)
    return _length((p[0] - (to_wall[0] - along * tp[0]), p[1] - (to_wall[1] - along * tp[1]))) <= TOL


def _distance_part(a: _Answer) -> None:
    """u_fw_pp lies along u_fw_p with the signed length |u_fw_p| - d_fw: toward the wall when the robot is
    farther than d_fw, away from it when closer, zero at d_fw."""
    p, pp = a["u_fw_p"], a["u_fw_pp"]
    n = _length(p)
    if n <= 1e-9:
        raise Mismatch(
            f"{a.where} your u_fw_p was {_v(p)}: u_fw_pp is built along u_fw_p, which must point "
            "to the wall (the u_fw_p check says more)"
        )
    along = _dot(pp, p) / n
    if abs(_cross(pp, p)) / n > TOL or abs(along - (n - a.d_fw)) > TOL:
        raise Mismatch(
            f"{a.where} with your u_fw_p = {_v(p)} (the robot {fmt(n)} m from the wall) your u_fw_pp "
            f"was {_v(pp)}: expected u_fw_p - d_fw * u_fw_p / |u_fw_p|, along u_fw_p and "
            f"{fmt(n)} - {fmt(a.d_fw)} = {fmt(n - a.d_fw)} m long (toward the point d_fw from the "
            "wall, zero at d_fw)"
        )


def _u_fw(a: _Answer) -> None:
    """u_fw is d_fw times u_fw_tp plus the distance part: the one it must be (from the student's u_fw_p),
    or the student's own u_fw_pp when that one is wrong (its check already says so). Judged on what u_fw
    must be, not only on the student's u_fw_pp: the course's sp14 code keeps the unit vector of u_fw_p
    under that name and writes u_fw = d_fw*u_fw_tp + (u_fw_p - d_fw*u_fw_pp), which is right (issue 21)."""
    tp, p, pp, u = a["u_fw_tp"], a["u_fw_p"], a["u_fw_pp"], a["u_fw"]
    if _length(tp) <= 1e-9:
        raise Mismatch(
            f"{a.where} your u_fw_tp was {_v(tp)}: u_fw needs the direction along the wall (the "
            "u_fw_tp check says more)"
        )
    n = _length(p)
    parts = [pp] + ([(p[0] - a.d_fw * p[0] / n, p[1] - a.d_fw * p[1] / n)] if n > 1e-9 else [])
    if all(_length((u[0] - part[0] - a.d_fw * tp[0], u[1] - part[1] - a.d_fw * tp[1])) > TOL
           for part in parts):
        raise Mismatch(
            f"{a.where} your u_fw was {_v(u)} with u_fw_tp = {_v(tp)} and u_fw_p = {_v(p)}: expected "
            f"d_fw * u_fw_tp + u_fw_pp = {_v(_plus(a.d_fw, tp, parts[-1]))}, the distance part u_fw_pp "
            "being u_fw_p - d_fw * u_fw_p / |u_fw_p|"
        )


def _plus(k: float, v: tuple[float, float], w: tuple[float, float]) -> tuple[float, float]:
    return (k * v[0] + w[0], k * v[1] + w[1])


def settings(ctx: Context) -> Outcome:
    """QBSupervisor.__init__ sets fw_direction to a side and d_fw to a distance the IR sensors can see."""
    answer = ctx.probe("wall_settings")
    if not isinstance(answer, dict):
        raise Mismatch("QBSupervisor gave no settings")
    direction = answer.get("fw_direction")
    if direction not in ("left", "right"):
        return Outcome(0.0, f"your fw_direction was {describe(direction)}, expected 'left' or 'right'")
    d_fw = number(answer.get("d_fw"), "your d_fw")
    if not IR_RANGE[0] < d_fw < IR_RANGE[1]:
        return Outcome(
            0.0,
            f"your d_fw was {fmt(d_fw)} m: the IR sensors see from {IR_RANGE[0]} to {IR_RANGE[1]} "
            "m, so the wall can only be followed at a distance in between (0.15 to 0.2 m work)",
            {"d_fw": d_fw},
        )
    return Outcome(1.0, f"fw_direction {direction!r}, d_fw {fmt(d_fw)} m", {"d_fw": d_fw})


def laps_done(direction: str) -> Callable[[tuple[float, float, float]], LapsDone]:
    """The lap runs' stop rule, from the run's true start: they end once LAPS laps are done, as the original
    test did ("the loop breaks at that moment"), so a robot is judged on the laps it was asked for, not on
    what it does after them (and a lap run costs about half its 90 s)."""
    return lambda start: LapsDone(gate(direction), LAPS, start[:2])


def run_settings(direction: str, theta0: float, d_fw: float | None) -> dict:
    """The supervisor settings of a lap run: v, the side, the start heading of the estimate (the original
    test set the true pose and the estimate alike) and, for a variant, d_fw (None: the student's own)."""
    settings = {"v": V, "fw_direction": direction, "estimate": [0.0, 0.0, theta0], "state": "follow_wall"}
    return settings if d_fw is None else {**settings, "d_fw": d_fw}


def judge_laps(
    steps: dict,
    collision: dict | None,
    direction: str,
    d_fw: float,
    obstacle: list,
    dt: float,
) -> tuple[bool, str, dict]:
    """Two laps through the gate, no collision, and once the robot found the wall (after the first SETTLE
    seconds) the median distance to `obstacle` (its polygons) within DISTANCE_TOL of d_fw and a turning
    rate of at most MAX_TURNING: (passed, why, figures). `steps`: a trace's columns x, y, theta, t, of a
    run stopped by `laps_done` (the figures are of the run until the laps were done)."""
    xs, ys, thetas, ts = steps["x"], steps["y"], steps["theta"], steps["t"]
    counted = laps(xs, ys, gate(direction))
    done = max(counted)
    first = int(round(SETTLE / dt))
    median = median_distance(xs[first:], ys[first:], obstacle) if len(xs) > first else None
    turning = turning_rate(thetas[first:], dt)
    t = ts[counted.index(LAPS)] if done >= LAPS else None
    figures = {"laps": done, "d_fw": d_fw, "median_distance": median, "t_laps": t, "turning_rate": turning}
    zigzag = turning is not None and turning > MAX_TURNING
    swings = (
        f"it turned on average {turning:.2f} rad/s once it found the wall (at most {MAX_TURNING:g}): it "
        "swings across the line at d_fw instead of driving along the wall (u_fw_tp carries it along)"
        if zigzag else ""
    )
    if collision is not None:
        before = f"; before that {swings}" if swings else ""
        return False, f"touched an obstacle at t = {collision['t']:.2f} s{before}. {LAP_HINT}", figures
    if done < LAPS:
        return (
            False,
            (
                f"drove {max(done, 0)} lap(s) around the obstacle in {ts[-1]:g} s ({LAPS} expected in "
                f"{SECONDS:g} s){'; ' + swings if swings else ''}. {LAP_HINT}"
            ),
            figures,
        )
    if zigzag:
        return False, f"{LAPS} laps in {t:.1f} s, but {swings}. {LAP_HINT}", figures
    if median is None or abs(median - d_fw) > DISTANCE_TOL:
        shown = "no" if median is None else f"a median distance of {fmt(median)} m"
        return (
            False,
            (
                f"{LAPS} laps in {t:.1f} s, but kept {shown} from the obstacle, not about d_fw = "
                f"{fmt(d_fw)} m (within {DISTANCE_TOL} m). {LAP_HINT}"
            ),
            figures,
        )
    return (
        True,
        f"{LAPS} laps in {t:.1f} s without touching the obstacle, about {fmt(median)} m from it",
        figures,
    )


# What judge_laps compares with a limit (grader.margins): the reference keeps its distance from each.
LAPS_DONE = Limit("laps", "", LAPS, above=True)
OFF_D_FW = Limit("median distance off d_fw", "m", DISTANCE_TOL, above=False)
TURNING = Limit("turning rate", "rad/s", MAX_TURNING, above=False)


def lap_margins(margins: Margins, figures: dict, clearance: float | None, run: str) -> None:
    """The figures of one lap run (judge_laps's, and the run's TRUE clearance) against their limits."""
    margins.add(CLEARANCE, clearance, run)
    margins.add(LAPS_DONE, figures["laps"], run)
    median = figures["median_distance"]
    margins.add(OFF_D_FW, None if median is None else abs(median - figures["d_fw"]), run)
    margins.add(TURNING, figures["turning_rate"], run)


def _laps(
    ctx: Context, check_id: str, direction: str, theta0: float, d_fw: float | None, label: str
) -> tuple[bool, str, dict, scenarios.Run]:
    """One run of the original test 6.x: v, direction and the start heading (true pose and estimate) set,
    d_fw the student's own (None) or the variant's; until the laps are done (laps_done), at most 90 s;
    judged by judge_laps."""
    if d_fw is None:
        answer = ctx.probe("wall_settings")
        d_fw = number(answer.get("d_fw") if isinstance(answer, dict) else None, "your d_fw")
        settings = run_settings(direction, theta0, None)
    else:
        settings = run_settings(direction, theta0, d_fw)
    world = load_world(ctx.config.world)
    session, note = earlier.scenario_session(ctx)  # the course's versions of the earlier weeks' parts
    r = scenarios.run(ctx, label, settings, SECONDS, world=world, start=(0.0, 0.0, theta0), session=session,
                      stop_rule=laps_done(direction))
    scenarios.keep(ctx, check_id, r)
    dt = ctx.config.dt
    ok, text, figures = judge_laps(r.trace.steps, r.collision, direction, d_fw, obstacle(world), dt)
    details = {**r.metrics, **figures, "problem": r.problem, "traces": scenarios.trace_keys([r])}
    if r.problem:
        return False, r.problem, details, r
    return ok, then(text, f"Note: {note}" if note else ""), details, r


def obstacle(world) -> list:
    """The obstacle the robot follows: the world's polygons other than the four arena walls (the L)."""
    return list(world.obstacles[:-4])


def _visible(direction: str, theta0: float):
    check_id = f"week6.laps.{direction}"

    def run(ctx: Context) -> Outcome:
        label = f"following the wall on the {direction}, starting at heading {fmt(theta0)}, your d_fw"
        ok, text, details, r = _laps(ctx, check_id, direction, theta0, None, label)
        label += f" = {fmt(details['d_fw'])} m" if "d_fw" in details else ""
        margins = Margins()
        _margins(margins, details, r)
        return Outcome(float(ok), f"{label}: {text}", {**details, "margins": margins.to_json()},
                       status=scenarios.status_of([r]))

    run.__name__ = direction
    return run


def hidden_laps(ctx: Context) -> Outcome:
    from grader.practice import not_here, variants_to_run

    picks = variants_to_run(ctx, 6, lambda data: hidden_picks(data, ctx.seed))
    if not picks:
        return Outcome(0.0, not_here(ctx), status="error")
    good, lines, runs, done, margins = 0, [], [], [], Margins()
    for v in picks:
        label = f"on the {v['direction']}, start heading {fmt(v['theta0'])}, d_fw = {fmt(v['d_fw'])} m"
        ok, text, details, r = _laps(ctx, "week6.laps.hidden", v["direction"], v["theta0"], v["d_fw"], label)
        good += ok
        lines.append(f"{label}: {text}")
        runs.append({"variant": v, **details})
        done.append(r)
        _margins(margins, details, r)
    return Outcome(
        good / len(picks),
        "; ".join(lines),
        {"runs": runs, "traces": scenarios.trace_keys(done), "margins": margins.to_json()},
        status=scenarios.status_of(done),
    )


def _margins(margins: Margins, details: dict, r: scenarios.Run) -> None:
    if not r.problem and "laps" in details:  # a broken run's verdict is the error, not a figure
        lap_margins(margins, details, scenarios.clearance_of(r), r.label)


CHECKS = [
    Check(
        "week6.follow_wall.sensors",
        "p_1, p_2: the two closest IR points on the chosen side",
        "property",
        1.0,
        sensors,
        FW,
    ),
    Check(
        "week6.follow_wall.tangent",
        "u_fw_t along the wall, u_fw_tp its unit vector",
        "property",
        1.0,
        _vectors_check("week6.follow_wall.tangent", _tangent, "u_fw_tp is the unit vector along p_2 - p_1"),
        FW,
    ),
    Check(
        "week6.follow_wall.perpendicular",
        "u_fw_p: to the wall, perpendicular, the distance long",
        "property",
        1.0,
        _vectors_check(
            "week6.follow_wall.perpendicular",
            _perpendicular,
            "u_fw_p is perpendicular to the wall, as long as the distance to it",
        ),
        FW,
    ),
    Check(
        "week6.follow_wall.distance",
        "u_fw_pp: toward d_fw from the wall, zero at d_fw",
        "property",
        1.0,
        _vectors_check("week6.follow_wall.distance", _distance_part, "u_fw_pp is zero at d_fw"),
        FW,
    ),
    Check(
        "week6.follow_wall.u_fw",
        "u_fw = d_fw * u_fw_tp + u_fw_pp",
        "property",
        1.0,
        _vectors_check("week6.follow_wall.u_fw", _u_fw, "u_fw combines u_fw_tp and u_fw_pp"),
        FW,
    ),
    Check(
        "week6.supervisor.settings",
        "QBSupervisor sets fw_direction and d_fw",
        "property",
        0.5,
        settings,
        SUPERVISOR,
    ),
    Check(
        "week6.laps.left",
        "two laps with the wall on the left (your d_fw): no collision, near d_fw",
        "scenario",
        2.0,
        _visible("left", 0.0),
        ALL,
        plots=("trajectory", "signals:u_fw,u_fw_t,u_fw_p"),
    ),
    Check(
        "week6.laps.right",
        "two laps with the wall on the right (your d_fw): no collision, near d_fw",
        "scenario",
        2.0,
        _visible("right", math.pi),
        ALL,
        plots=("trajectory", "signals:u_fw,u_fw_t,u_fw_p"),
    ),
    Check(
        "week6.laps.hidden",
        "two laps in variants drawn per seed (side, start heading, d_fw)",
        "scenario",
        1.5,
        hidden_laps,
        ALL,
        visibility="hidden",
    ),
]


def hidden_picks(data: dict, seed: int) -> list[dict]:
    """The hidden variants `seed` draws from the hidden set `data` (grader.hidden.identity records them)."""
    from grader.hidden.draw import draw, heading_quarter

    return draw(data["variants"], 3, f"{seed}:week6-variants",
                lambda v: (v["direction"], heading_quarter(v["theta0"])))
