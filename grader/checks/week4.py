"""Week 4 checks: the transformation matrix, the IR points in the robot and world frames, the sensor gains,
u_ao, and 60 s of avoiding obstacles in the week-4 world (and, hidden, from start poses drawn per seed).

apply_sensor_geometry and u_ao are probed with a correct get_transformation_matrix put in place of the
student's, so a mistake in the matrix costs the matrix check (and the runs), not every check.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np

from grader import reference as ref
from grader import scenarios
from grader.checks import Check, Context, Mismatch, Outcome
from grader.checks.answers import fmt, matrix, number, vector
from grader.domains import Floats, Lists
from grader.margins import Limit, Margins
from grader.properties import run_property
from simiam.world import World, load_world

AO = ("avoid_obstacles.py",)
ALL = (
    "differential_drive.py",
    "quickbot.py",
    "go_to_angle.py",
    "go_to_goal.py",
    "avoid_obstacles.py",
    "qb_supervisor.py",
)
# The scenario's v and first state and its length come from the week's declaration (ctx.config).
HIDDEN_SECONDS = 30.0  # each hidden variant was checked for 60 s with the reference solution
MIN_PATH = 1.0  # "really moving": at least this many metres driven in the run
PATH = Limit("path length", "m", MIN_PATH, above=True)
POSE = [0.3, -0.2, 0.7]
COLLISION_HINT = (
    "Hint: the robot steers along u_ao: the checks of the IR points, the gains, u_ao and theta_ao say which "
    "part is wrong; if they all pass, tune Kp, Ki, Kd or sensor_gains (replay the run in the report)"
)
STILL_HINT = "Hint: AvoidObstacles must keep driving at inputs.v and only steer (w) away from obstacles"

_coord = Floats(-1.5, 1.5)
_angle = Floats(-math.pi, math.pi)
_distance = Floats(0.04, 0.3)


def _pose_words(x: float, y: float, theta: float) -> str:
    return f"({fmt(x)}, {fmt(y)}, {fmt(theta)})"


def transformation(ctx: Context) -> Outcome:
    def case(ctx: Context, x: float, y: float, theta: float) -> None:
        got = matrix(
            ctx.probe("transformation_matrix", x=x, y=y, theta=theta),
            3,
            3,
            f"get_transformation_matrix{_pose_words(x, y, theta)}",
        )
        want = ref.matrix_of(x, y, theta)  # read off where the simulator places points
        for i in range(3):
            for j in range(3):
                if abs(got[i][j] - want[i][j]) > 1e-6:
                    raise Mismatch(
                        f"get_transformation_matrix{_pose_words(x, y, theta)}: row {i + 1}, column "
                        f"{j + 1} was {fmt(got[i][j])}, expected {fmt(want[i][j])} "
                        "([cos -sin x], [sin cos y], [0 0 1])"
                    )

    return run_property(
        ctx,
        "week4.transform.matrix",
        {"x": _coord, "y": _coord, "theta": _angle},
        case,
        examples=[{"x": 0.0, "y": 0.0, "theta": 0.5}, {"x": 1.0, "y": -2.0, "theta": 0.0}],
        passed="T(x, y, theta) is right",
    )


def frames(ctx: Context, pose: list) -> list:
    """The matrices the probes put in place of the student's get_transformation_matrix: one per sensor
    mount and one for the robot's pose, from the simulator's placement (grader.reference.matrix_of)."""
    return [[*at, ref.matrix_of(*at)] for at in (*ctx.spec.ir_mounts, tuple(pose))]


def _geometry(ctx: Context, distances: list, pose: list) -> tuple[list, list]:
    answer = ctx.probe("sensor_geometry", distances=distances, pose=pose, frames=frames(ctx, pose))
    if not isinstance(answer, list) or len(answer) != 2:
        raise Mismatch(
            "apply_sensor_geometry must return two 3x5 matrices (ir_distances_rf, ir_distances_wf)"
        )
    where = f"with distances {', '.join(fmt(d) for d in distances)} at pose {_pose_words(*pose)}"
    return (
        matrix(answer[0], 3, 5, f"{where} your ir_distances_rf"),
        matrix(answer[1], 3, 5, f"{where} your ir_distances_wf"),
    )


def _frame_check(frame: str):
    def case(ctx: Context, distances: list, x: float, y: float, theta: float) -> None:
        pose = [x, y, theta]
        rf, wf = _geometry(ctx, distances, pose)
        if frame == "robot":
            got, want = rf, ref.sensor_points(ctx.spec, distances, pose)[0]
            hint = "T(x_s, y_s, theta_s) of the sensor's mount times (d, 0, 1)"
        else:  # from the student's own robot-frame points, so a robot-frame mistake is not counted twice
            got, want = (
                wf,
                [ref.place(pose, (rf[0][i], rf[1][i])) for i in range(5)],
            )
            hint = "T(x, y, theta) of the robot's pose times the robot-frame point"
        for i in range(5):
            wx, wy = want[i]
            if abs(got[0][i] - wx) > 1e-6 or abs(got[1][i] - wy) > 1e-6 or abs(got[2][i] - 1) > 1e-6:
                raise Mismatch(
                    f"with IR distance {fmt(distances[i])} on sensor {i + 1} and the robot at "
                    f"{_pose_words(*pose)} your {frame}-frame point was ({fmt(got[0][i])}, "
                    f"{fmt(got[1][i])}, {fmt(got[2][i])}), expected ({fmt(wx)}, {fmt(wy)}, 1): {hint}"
                )

    strategies = {
        "distances": Lists(_distance, min_size=5, max_size=5),
        "x": _coord,
        "y": _coord,
        "theta": _angle,
    }

    def run(ctx: Context) -> Outcome:
        return run_property(
            ctx,
            f"week4.sensor_geometry.{frame}_frame",
            strategies,
            case,
            examples=[{"distances": [0.21, 0.3, 0.3, 0.21, 0.3], "x": 0.1, "y": -0.1, "theta": -1.578}],
            passed=f"the IR points in the {frame} frame are right",
        )

    run.__name__ = f"{frame}_frame"
    return run


def _u_aos(ctx: Context, readings: list[list]) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """For each set of IR distances (at POSE): u_ao and the vectors from the robot to the student's own
    world-frame IR points, probed in one request and checked one by one."""
    answers = ctx.probe_each("avoid_obstacles", [_avoid_args(ctx, distances, POSE) for distances in readings])
    for distances, answer in zip(readings, answers, strict=False):
        u_ao, vectors, _ = _avoid_answer(answer, distances, POSE)
        yield u_ao, vectors


def _avoid_args(ctx: Context, distances: list, pose: list) -> dict:
    """The avoid_obstacles probe's inputs: the readings, the pose, the week's v and the frames."""
    return {"distances": distances, "pose": pose, "v": ctx.config.settings.v, "frames": frames(ctx, pose)}


def _avoid_once(ctx: Context, distances: list, pose: list) -> tuple[np.ndarray, np.ndarray, dict]:
    """One AvoidObstacles.execute: u_ao, the vectors to the student's own IR points, and the raw answer."""
    return _avoid_answer(ctx.probe("avoid_obstacles", **_avoid_args(ctx, distances, pose)), distances, pose)


def _avoid_answer(answer: Any, distances: list, pose: list) -> tuple[np.ndarray, np.ndarray, dict]:
    """The untrusted answer of one avoid_obstacles probe, validated: (u_ao, vectors, answer)."""
    if not isinstance(answer, dict):
        raise Mismatch("AvoidObstacles.execute gave no answer")
    where = f"with IR distances {', '.join(fmt(d) for d in distances)}"
    if answer.get("u_ao") is None:
        raise Mismatch(f"{where} AvoidObstacles kept no u_ao")
    u_ao = answer.get("u_ao")
    if isinstance(u_ao, list) and all(isinstance(c, list) and len(c) == 1 for c in u_ao):
        u_ao = [c[0] for c in u_ao]  # a 2x1 column vector is fine too
    u_ao = np.array(vector(u_ao, 2, f"{where} your u_ao"))
    wf = answer.get("ir_distances_wf")
    points = np.array(
        matrix(
            wf,
            len(wf) if isinstance(wf, list) and len(wf) in (2, 3) else 3,
            5,
            f"{where} your ir_distances_wf",
        )
    )
    return u_ao, points[:2] - np.array([[pose[0]], [pose[1]]]), answer


_GAIN_PROBES = [
    [0.3] * 5,
    [0.1, 0.3, 0.3, 0.3, 0.3],
    [0.3, 0.1, 0.3, 0.3, 0.3],
    [0.3, 0.3, 0.1, 0.3, 0.3],
    [0.3, 0.3, 0.3, 0.1, 0.3],
    [0.3, 0.3, 0.3, 0.3, 0.1],
]


def symmetric_gains(ctx: Context) -> Outcome:
    """The gains behind u_ao (solved from six readings): the same for sensors 1/5 and 2/4, not all 0."""
    rows, rhs = [], []
    for u_ao, vectors in _u_aos(ctx, _GAIN_PROBES):
        rows += [vectors[0], vectors[1]]
        rhs += [u_ao[0], u_ao[1]]
    rows = [[float(value) for value in row] for row in rows]
    rhs = [float(value) for value in rhs]
    # exact rationals and plain sums: the grader's side of the comparison is the same on every CPU
    gains = ref.least_squares(rows, rhs)
    residual = max(abs(ref.dot(row, gains) - value) for row, value in zip(rows, rhs, strict=True))
    details = {"sensor_gains": gains, "fit_residual": residual}
    words = ", ".join(fmt(g) for g in gains)
    if residual > 1e-6 * max(1.0, max(abs(value) for value in rhs)):
        return Outcome(
            0.0,
            "with six sets of IR readings (all 0.3 m, then each sensor in turn at 0.1 m), no one set of five "
            "sensor gains makes u_ao the weighted sum of the vectors from the robot to your IR points (the "
            f"best fixed gains miss u_ao by {fmt(residual)} m): sensor_gains must be fixed numbers, the "
            "same whatever the sensors read, and u_ao = sum of gain_i * u_i",
            details,
        )
    scale = max(abs(g) for g in gains)
    if scale < 1e-9:
        return Outcome(0.0, "your sensor_gains are all 0, so u_ao is always 0", details)
    if abs(gains[0] - gains[4]) > 1e-6 * scale or abs(gains[1] - gains[3]) > 1e-6 * scale:
        return Outcome(
            0.0,
            f"your sensor gains are {words}: sensors 1 and 5, and 2 and 4, must weigh the same "
            "(left and right alike)",
            details,
        )
    return Outcome(1.0, f"sensor gains {words} are symmetric", details)


def points_away(ctx: Context) -> Outcome:
    """An obstacle close to one sensor turns u_ao away from it: away from the direction of that sensor's
    IR point as the student's own geometry puts it (a geometry mistake costs the geometry checks only)."""
    readings = [[0.3] * 5]
    for i in range(5):
        distances = [0.3] * 5
        distances[i] = 0.06
        readings.append(distances)
    answers = _u_aos(ctx, readings)
    free, vectors = next(answers)
    for i, (u_ao, _) in enumerate(answers):
        vector = [float(vectors[0, i]), float(vectors[1, i])]
        length = max(math.sqrt(ref.dot(vector, vector)), 1e-12)
        direction = [vector[0] / length, vector[1] / length]
        towards = ref.dot([float(u_ao[0] - free[0]), float(u_ao[1] - free[1])], direction)
        if towards >= -1e-9:
            return Outcome(
                0.0,
                f"with an obstacle 0.06 m in front of sensor {i + 1} (the others reading 0.3 m), u_ao moved "
                f"{fmt(towards)} m toward that sensor's IR point instead of away from it (u_ao with all "
                f"sensors at 0.3 m: ({fmt(float(free[0]))}, {fmt(float(free[1]))}), now "
                f"({fmt(float(u_ao[0]))}, {fmt(float(u_ao[1]))})): weigh each u_i, the vector from the "
                "robot to IR point i, by a positive gain",
                {"sensor": i + 1, "toward_obstacle": towards},
            )
    return Outcome(1.0, "an obstacle in front of any sensor turns u_ao away from it")


def heading(ctx: Context) -> Outcome:
    """theta_ao is the direction of the student's own u_ao, and e_k = theta_ao - theta wrapped."""

    def case(ctx: Context, distances: list, theta: float) -> None:
        pose = [0.3, -0.2, theta]
        u_ao, _, answer = _avoid_once(ctx, distances, pose)
        where = (
            f"with IR distances {', '.join(fmt(d) for d in distances)} and the robot at "
            f"{_pose_words(*pose)}"
        )
        theta_ao = number(answer.get("theta_ao"), f"{where} your theta_ao")
        e_k = number(answer.get("e_k"), f"{where} your heading error e_k")
        want = ref.bearing(float(u_ao[0]), float(u_ao[1]))
        if ref.angle_diff(theta_ao, want) > 1e-6:
            raise Mismatch(
                f"{where} your u_ao was ({fmt(float(u_ao[0]))}, {fmt(float(u_ao[1]))}) and theta_ao "
                f"{fmt(theta_ao)}, expected its direction atan2(u_ao[1], u_ao[0]) = {fmt(want)}"
            )
        want_e = ref.wrap(theta_ao - theta)
        if abs(e_k - want_e) > 1e-6:
            raise Mismatch(
                f"{where} your theta_ao was {fmt(theta_ao)} and your error e_k {fmt(e_k)}, expected "
                f"theta_ao - theta = {fmt(theta_ao - theta)} wrapped into [-pi, pi]: {fmt(want_e)}"
            )

    examples = [
        {"distances": [0.3, 0.3, 0.1, 0.3, 0.3], "theta": 0.0},
        {"distances": [0.3, 0.1, 0.3, 0.3, 0.3], "theta": 3.0},
        {"distances": [0.3, 0.3, 0.3, 0.1, 0.3], "theta": -3.0},
    ]
    return run_property(
        ctx,
        "week4.avoid.heading",
        {"distances": Lists(_distance, min_size=5, max_size=5), "theta": _angle},
        case,
        examples=examples,
        max_examples=15,
        passed="theta_ao follows u_ao and the error is wrapped",
    )


def _variant(world: World, turn: int, of: int, mirror: bool) -> World:
    """The world mirrored in y (if asked) and rotated about the start by 2*pi*turn/of: the robot starts
    facing another way, and its estimate still starts at (0, 0, 0) as the student's supervisor expects."""
    theta = turn * 2 * math.pi / of
    moved = []
    for poly in world.obstacles:
        q = [(x, -y) if mirror else (x, y) for x, y in poly]
        moved.append(ref.placed((0.0, 0.0, theta), q))
    label = f"week-4 world{' mirrored' if mirror else ''}, turned {360 * turn / of:g} degrees"
    return World(label, moved)


def _avoid(
    ctx: Context, check_id: str, world: World, label: str, seconds: float, margins: Margins
) -> tuple[bool, str, dict, scenarios.Run]:
    r = scenarios.run(ctx, label, ctx.config.settings.as_dict(), seconds, world=world)
    scenarios.keep(ctx, check_id, r)
    length = r.metrics["path_length"]
    details = {
        **r.metrics,
        "max_displacement": scenarios.max_displacement(r.trace),
        "problem": r.problem,
        "traces": scenarios.trace_keys([r]),
    }
    scenarios.add_margins(margins, r)
    if not r.problem:
        margins.add(PATH, length, r.label)
    if r.problem:
        return False, r.problem, details, r
    if r.collision is not None:
        return False, f"collided at t = {r.collision['t']:.2f} s. {COLLISION_HINT}", details, r
    if length < MIN_PATH:
        return (
            False,
            f"drove only {length:.2f} m in {seconds:g} s (at least {MIN_PATH:g} m expected). {STILL_HINT}",
            details,
            r,
        )
    gap = r.metrics.get("min_clearance")
    closest = f", never closer than {gap:.2f} m to an obstacle" if gap is not None else ""
    return True, f"no collision in {seconds:g} s, {length:.1f} m driven{closest}", details, r


def week4_world(ctx: Context) -> Outcome:
    margins = Margins()
    ok, text, details, r = _avoid(
        ctx, "week4.avoid.week4_world", load_world(ctx.config.world), "week-4 world", ctx.config.seconds,
        margins,
    )
    return Outcome(float(ok), f"week-4 world, v = {ctx.config.settings.v}: {text}",
                   {**details, "margins": margins.to_json()}, status=scenarios.status_of([r]))


def other_starts(ctx: Context) -> Outcome:
    from grader.practice import not_here, variants_to_run

    picks = variants_to_run(ctx, 4, lambda data: hidden_picks(data, ctx.seed))
    if not picks:
        return Outcome(0.0, not_here(ctx), status="error")
    good, lines, runs, done, margins = 0, [], [], [], Margins()
    for v in picks:
        world = _variant(load_world("week4"), v["turn"], v["of"], v["mirror"])
        ok, text, details, r = _avoid(ctx, "week4.avoid.other_starts", world, world.name, HIDDEN_SECONDS,
                                      margins)
        good += ok
        lines.append(f"{world.name}: {text}")
        runs.append({"variant": v, **details})
        done.append(r)
    return Outcome(
        good / len(picks),
        "; ".join(lines),
        {"runs": runs, "traces": scenarios.trace_keys(done), "margins": margins.to_json()},
        status=scenarios.status_of(done),
    )


CHECKS = [
    Check("week4.transform.matrix", "get_transformation_matrix", "property", 1.0, transformation, AO),
    Check(
        "week4.sensor_geometry.robot_frame",
        "IR points in the robot frame",
        "property",
        1.0,
        _frame_check("robot"),
        AO,
    ),
    Check(
        "week4.sensor_geometry.world_frame",
        "IR points in the world frame",
        "property",
        1.0,
        _frame_check("world"),
        AO,
    ),
    Check("week4.avoid.symmetric_gains", "sensor gains are symmetric", "property", 0.5, symmetric_gains, AO),
    Check("week4.avoid.points_away", "u_ao points away from obstacles", "property", 1.0, points_away, AO),
    Check(
        "week4.avoid.heading",
        "theta_ao is the direction of u_ao, the error wrapped",
        "property",
        1.0,
        heading,
        AO,
    ),
    Check(
        "week4.avoid.week4_world",
        "60 s in the week-4 world: no collision, really moving",
        "scenario",
        2.0,
        week4_world,
        ALL,
    ),
    Check(
        "week4.avoid.other_starts",
        "30 s in variants of the week-4 world drawn per seed",
        "scenario",
        1.5,
        other_starts,
        ALL,
        visibility="hidden",
    ),
]


def hidden_picks(data: dict, seed: int) -> list[dict]:
    """The hidden variants `seed` draws from the hidden set `data` (grader.hidden.identity records them)."""
    from grader.hidden.draw import draw, turn_quarter

    return draw(data["variants"], 3, f"{seed}:week4-variants",
                lambda v: (turn_quarter(v["turn"], v["of"]), v["mirror"]))
