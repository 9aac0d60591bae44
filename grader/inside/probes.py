"""Probes: small functions that run INSIDE the sandbox worker against the student's loaded code.

The worker answers `{"op": "probe", "name": ..., "args": {...}}` with `dispatch(sub, name, args)`, where
`sub` is the loaded submission (`simiam.course.loader.Submission`). A probe calls the student's functions
with the inputs the grader chose and returns what came back as plain JSON. It decides nothing: everything
it returns is untrusted, and the grading process validates and scores it (grader/checks/).

Every probe takes `week` (1..4) so it can build the robot the student code sees.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from typing import Any

from simiam.control.controller import Inputs
from simiam.control.pose import Pose2D
from simiam.control.robot_view import RobotView
from simiam.course.weeks import get_week

__all__ = [
    "avoid_obstacles",
    "blend",
    "ensure_w",
    "follow_wall",
    "go_to_goal",
    "ir_distances",
    "odometry",
    "sensor_geometry",
    "switching",
    "transformation_matrix",
    "uni_to_diff",
    "wall_settings",
    "week7_progress",
    "week7_progress_point",
    "week7_sliding",
    "week7_step",
]

_MAX_ITEMS = 64  # a probe answer is never bigger than a few 3x5 matrices or a tick sequence


def plain(value: Any, depth: int = 0) -> Any:
    """Student return values as JSON: numbers as float, sequences (numpy included) as lists.

    Anything else becomes {"type": name}, so the grader can say what came back instead of crashing.
    """
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, numbers.Real):
        x = float(value)
        return x if math.isfinite(x) else repr(x)  # JSON has no NaN/inf: the grader sees "nan"
    if depth < 3 and hasattr(value, "tolist") and not isinstance(value, numbers.Number):
        try:
            value = value.tolist()
        except Exception:  # noqa: BLE001 - a student object may do anything in tolist
            return {"type": type(value).__name__}
    if depth < 3 and isinstance(value, (list, tuple)):
        return [plain(v, depth + 1) for v in value[:_MAX_ITEMS]]
    return {"type": type(value).__name__}


def _robot(sub, week: int) -> RobotView:
    return RobotView(get_week(week).spec, sub)


def _supervisor(sub, week: int, start=(0.0, 0.0, 0.0)):
    robot = _robot(sub, week)
    supervisor = sub.module("qb_supervisor").QBSupervisor()
    supervisor.attach_robot(robot, Pose2D(*start))
    return supervisor, robot


def uni_to_diff(sub, week: int, v: float, w: float) -> Any:
    """differential_drive.uni_to_diff(robot, v, w)."""
    return plain(sub.module("differential_drive").uni_to_diff(_robot(sub, week), v, w))


def odometry(sub, week: int, ticks: list, start=(0.0, 0.0, 0.0)) -> Any:
    """QBSupervisor.update_odometry after each [right, left] cumulative tick pair; the estimates."""
    supervisor, robot = _supervisor(sub, week, start)
    out = []
    for right, left in ticks:
        robot.encoders[0].ticks, robot.encoders[1].ticks = int(right), int(left)
        supervisor.update_odometry()
        out.append(plain(supervisor.state_estimate.unpack()))
    return out


def ir_distances(sub, week: int, raw: list) -> Any:
    """quickbot.get_ir_distances(robot) with the five sensors reading `raw`."""
    robot = _robot(sub, week)
    for sensor, value in zip(robot.ir_array, raw, strict=True):
        sensor._raw = int(value)
    return plain(robot.get_ir_distances())


def ensure_w(sub, week: int, v: float, w: float) -> Any:
    """QBSupervisor.ensure_w(robot, v, w) -> (vel_r, vel_l)."""
    supervisor, robot = _supervisor(sub, week)
    return plain(supervisor.ensure_w(robot, v, w))


_GAINS = ("Kp", "Ki", "Kd")


def _pinned(cls):
    """The student's controller class with its gains pinned once the grader has set them: a write to
    Kp/Ki/Kd inside execute is recorded in `_grader_overwrote` and ignored, so the terms are still checked
    with the grader's gains and the overwrite is reported once (week3.pid.memory), not as wrong arithmetic."""

    class Pinned(cls):
        def __setattr__(self, name, value):
            if name in _GAINS and self.__dict__.get("_grader_pin"):
                self.__dict__["_grader_overwrote"][name] = value
                return
            super().__setattr__(name, value)

    Pinned.__name__ = cls.__name__
    return Pinned


def go_to_goal(sub, week: int, gains: dict, calls: list, fresh: bool = False) -> Any:
    """GoToGoal.execute for a sequence of calls [{"pose": [x, y, theta], "goal": [x, y], "v": v, "dt": dt,
    "memory": {"E_k": .., "e_k_1": ..} (optional, set before the call)}].

    With `fresh` every call gets a new controller (no memory); otherwise one controller sees them all.
    Returns per call {"out": (v, w), "theta_g", "e_k" and "E_k" (what the controller stored for the next
    call: the provided code keeps e_k in e_k_1 and e_I in E_k), "overwrote": gains execute tried to set}.
    """
    robot = _robot(sub, week)
    cls = sub.module("go_to_goal").GoToGoal
    pinned = _pinned(cls) if "__slots__" not in vars(cls) else cls
    ctrl = None
    out = []
    for call in calls:
        if ctrl is None or fresh:
            ctrl = pinned()
            for name, value in gains.items():
                setattr(ctrl, name, value)
            if hasattr(ctrl, "__dict__"):
                ctrl.__dict__["_grader_overwrote"] = {}
                ctrl.__dict__["_grader_pin"] = True
        for name, value in (call.get("memory") or {}).items():
            if name in ("E_k", "e_k_1"):
                setattr(ctrl, name, value)
        x_g, y_g = call["goal"]
        inputs = Inputs(v=call["v"], x_g=x_g, y_g=y_g, theta_d=0.0)
        result = ctrl.execute(robot, Pose2D(*call["pose"]), inputs, call["dt"])
        overwrote = getattr(ctrl, "__dict__", {}).get("_grader_overwrote", {})
        out.append(
            {
                "out": plain(result),
                "theta_g": plain(getattr(ctrl, "theta_g", None)),
                "e_k": plain(getattr(ctrl, "e_k_1", None)),
                "E_k": plain(getattr(ctrl, "E_k", None)),
                "overwrote": {k: plain(v) for k, v in overwrote.items() if k in _GAINS},
            }
        )
    return out


def transformation_matrix(sub, week: int, x: float, y: float, theta: float) -> Any:
    """AvoidObstacles.get_transformation_matrix(x, y, theta)."""
    ctrl = sub.module("avoid_obstacles").AvoidObstacles()
    return plain(ctrl.get_transformation_matrix(x, y, theta))


def _given_matrices(ctrl: Any, frames: list | None) -> None:
    """Put the grader's matrices in place of the student's get_transformation_matrix for the calls a
    correct apply_sensor_geometry makes (each sensor's mount pose, the robot's pose), so a mistake in the
    matrix costs only its own check. `frames` is [[x, y, theta, matrix], ...], computed by the grader from
    the simulator's placement: this module holds no matrix maths (it runs next to student code). A call
    with other arguments gets the student's own matrix."""
    if not frames:
        return
    table = {(float(x), float(y), float(theta)): matrix for x, y, theta, matrix in frames}
    own = ctrl.get_transformation_matrix

    def get_transformation_matrix(x: float, y: float, theta: float) -> Any:
        given = table.get((float(x), float(y), float(theta)))
        return [list(row) for row in given] if given is not None else own(x, y, theta)

    ctrl.get_transformation_matrix = get_transformation_matrix


def sensor_geometry(sub, week: int, distances: list, pose: list, frames: list | None = None) -> Any:
    """AvoidObstacles.apply_sensor_geometry(robot, distances, pose) -> [rf, wf].

    The controller gets the grader's matrices (`frames`, see _given_matrices), so a mistake in
    get_transformation_matrix costs only its own check; a solution that builds the matrices inline is
    unaffected.
    """
    ctrl = sub.module("avoid_obstacles").AvoidObstacles()
    _given_matrices(ctrl, frames)
    return plain(ctrl.apply_sensor_geometry(_robot(sub, week), list(distances), Pose2D(*pose)))


def avoid_obstacles(sub, week: int, distances: list, pose: list, v: float = 0.2, dt: float = 0.033,
                    frames: list | None = None) -> Any:
    """AvoidObstacles.execute once with the IR distances fixed to `distances`: u_ao and the IR points."""
    robot = _robot(sub, week)
    setattr(robot, "get_ir_distances", lambda: list(distances))  # noqa: B010 - the conversion is checked elsewhere
    ctrl = sub.module("avoid_obstacles").AvoidObstacles()
    _given_matrices(ctrl, frames)
    result = ctrl.execute(robot, Pose2D(*pose), Inputs(v=v, x_g=0.0, y_g=0.0, theta_d=0.0), dt)
    return {
        "out": plain(result),
        "u_ao": plain(getattr(ctrl, "u_ao", None)),
        "ir_distances_wf": plain(getattr(ctrl, "ir_distances_wf", None)),
        # the provided code keeps theta_ao in theta_g and the error e_k in e_k_1
        "theta_ao": plain(getattr(ctrl, "theta_g", None)),
        "e_k": plain(getattr(ctrl, "e_k_1", None)),
    }


# the weeks that keep their probes in a module of their own (grader/inside/probes_weekN.py)
from grader.inside.probes_week5 import blend, switching  # noqa: E402
from grader.inside.probes_week6 import follow_wall, wall_settings  # noqa: E402
from grader.inside.probes_week7 import (  # noqa: E402
    week7_progress,
    week7_progress_point,
    week7_sliding,
    week7_step,
)

PROBES: dict[str, Callable[..., Any]] = {
    "uni_to_diff": uni_to_diff,
    "odometry": odometry,
    "ir_distances": ir_distances,
    "ensure_w": ensure_w,
    "go_to_goal": go_to_goal,
    "transformation_matrix": transformation_matrix,
    "sensor_geometry": sensor_geometry,
    "avoid_obstacles": avoid_obstacles,
    "blend": blend,
    "switching": switching,
    "follow_wall": follow_wall,
    "wall_settings": wall_settings,
    "week7_sliding": week7_sliding,
    "week7_progress": week7_progress,
    "week7_progress_point": week7_progress_point,
    "week7_step": week7_step,
}


def dispatch(sub, name: str, args: dict) -> Any:
    """Run probe `name` with `args` (the worker's entry point); KeyError for an unknown probe."""
    if name not in PROBES:
        raise KeyError(f"no probe named {name!r}")
    return PROBES[name](sub, **args)
