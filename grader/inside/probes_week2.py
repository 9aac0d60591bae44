"""Week 2's probes: uni_to_diff, odometry and the IR conversion. They run INSIDE the sandbox worker against
the student's loaded code (grader/inside/probes.py lists them), call it with the inputs the grader chose
and return what came back as plain JSON; they decide nothing."""

from __future__ import annotations

from typing import Any

from grader.inside.probing import exercises, plain, robot_for, supervisor_for

__all__ = ["ir_distances", "odometry", "uni_to_diff"]


@exercises("differential_drive.py:uni_to_diff")
def uni_to_diff(sub, week: int, v: float, w: float) -> Any:
    """differential_drive.uni_to_diff(robot, v, w)."""
    return plain(sub.module("differential_drive").uni_to_diff(robot_for(sub, week), v, w))


@exercises("qb_supervisor.py:QBSupervisor.update_odometry")
def odometry(sub, week: int, ticks: list, start=(0.0, 0.0, 0.0)) -> Any:
    """QBSupervisor.update_odometry after each [right, left] cumulative tick pair; the estimates."""
    supervisor, robot = supervisor_for(sub, week, start)
    out = []
    for right, left in ticks:
        robot.encoders[0].ticks, robot.encoders[1].ticks = int(right), int(left)
        supervisor.update_odometry()
        out.append(plain(supervisor.state_estimate.unpack()))
    return out


@exercises("quickbot.py:get_ir_distances")
def ir_distances(sub, week: int, raw: list) -> Any:
    """quickbot.get_ir_distances(robot) with the five sensors reading `raw`."""
    robot = robot_for(sub, week)
    for sensor, value in zip(robot.ir_array, raw, strict=True):
        sensor._raw = int(value)
    return plain(robot.get_ir_distances())
