"""Week-6 probes (run INSIDE the sandbox worker, like grader/inside/probes.py, which lists them): FollowWall
once with chosen IR distances, and the supervisor's follow-wall settings. They decide nothing."""

from __future__ import annotations

from typing import Any

from grader.inside.probing import exercises, plain, robot_for, supervisor_for
from simiam.control.controller import Inputs
from simiam.control.pose import Pose2D

__all__ = ["follow_wall", "wall_settings"]


@exercises("follow_wall.py:FollowWall.execute")
def follow_wall(sub, week: int, distances: list, pose: list, direction: str, d_fw: float, v: float = 0.15,
                dt: float = 0.05) -> Any:
    """FollowWall.execute once with the IR distances fixed to `distances`: the wall points and vectors.

    The IR points come from FollowWall's own (provided) apply_sensor_geometry, as in the course."""
    robot = robot_for(sub, week)
    setattr(robot, "get_ir_distances", lambda: list(distances))  # noqa: B010 - the conversion is checked elsewhere
    ctrl = sub.module("follow_wall").FollowWall()
    inputs = Inputs(v=v, x_g=0.0, y_g=0.0, theta_d=0.0, direction=direction, d_fw=d_fw)
    result = ctrl.execute(robot, Pose2D(*pose), inputs, dt)
    names = ("p_1", "p_2", "u_fw_t", "u_fw_tp", "u_fw_p", "u_fw_pp", "u_fw", "ir_distances_wf")
    return {"out": plain(result), "theta_fw": plain(getattr(ctrl, "theta_g", None)),
            **{name: plain(getattr(ctrl, name, None)) for name in names}}


@exercises("qb_supervisor.py:QBSupervisor.__init__")
def wall_settings(sub, week: int) -> Any:
    """What QBSupervisor.__init__ set for following a wall: d_fw and fw_direction."""
    supervisor, _ = supervisor_for(sub, week)
    return {"d_fw": plain(getattr(supervisor, "d_fw", None)),
            "fw_direction": plain(getattr(supervisor, "fw_direction", None))}
