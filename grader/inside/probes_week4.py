"""Week 4's probes: AvoidObstacles' matrix, sensor geometry and execute. They run INSIDE the sandbox worker
against the student's loaded code (grader/inside/probes.py lists them), call it with the inputs the grader
chose and return what came back as plain JSON; they decide nothing."""

from __future__ import annotations

from typing import Any

from grader.inside.probing import exercises, plain, robot_for
from simiam.control.controller import Inputs
from simiam.control.pose import Pose2D

__all__ = ["avoid_obstacles", "sensor_geometry", "transformation_matrix"]


@exercises("avoid_obstacles.py:AvoidObstacles.get_transformation_matrix")
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


@exercises("avoid_obstacles.py:AvoidObstacles.apply_sensor_geometry")
def sensor_geometry(sub, week: int, distances: list, pose: list, frames: list | None = None) -> Any:
    """AvoidObstacles.apply_sensor_geometry(robot, distances, pose) -> [rf, wf].

    The controller gets the grader's matrices (`frames`, see _given_matrices), so a mistake in
    get_transformation_matrix costs only its own check; a solution that builds the matrices inline is
    unaffected.
    """
    ctrl = sub.module("avoid_obstacles").AvoidObstacles()
    _given_matrices(ctrl, frames)
    return plain(ctrl.apply_sensor_geometry(robot_for(sub, week), list(distances), Pose2D(*pose)))


@exercises("avoid_obstacles.py:AvoidObstacles.__init__", "avoid_obstacles.py:AvoidObstacles.execute")
def avoid_obstacles(sub, week: int, distances: list, pose: list, v: float = 0.2, dt: float = 0.033,
                    frames: list | None = None) -> Any:
    """AvoidObstacles.execute once with the IR distances fixed to `distances`: u_ao and the IR points."""
    robot = robot_for(sub, week)
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
