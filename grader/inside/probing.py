"""What every probe shares (grader/inside/probes_weekN.py): the robot and the supervisor it builds for the
student's code, its answers as plain JSON, and the declaration of the student code it calls.

Runs INSIDE the sandbox worker, next to student code: it imports nothing trusted (tests/sandbox/
test_inside.py) and only what the worker has loaded anyway (its start-up stays cheap:
tests/sandbox/test_worker_start.py).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from typing import Any, TypeVar

from simiam.control.pose import Pose2D
from simiam.control.robot_view import RobotView
from simiam.course.weeks import get_week

_MAX_ITEMS = 64  # a probe answer is never bigger than a few 3x5 matrices or a tick sequence

Probe = TypeVar("Probe", bound=Callable[..., Any])


def exercises(*functions: str) -> Callable[[Probe], Probe]:
    """Declare the student functions a probe runs, each "file:Class.method" or "file:function" as the
    week declares its blocks (Placeholder file and scope). Data only: tests/course/test_week_parts.py
    checks that each is a block the probing week (or an earlier one) declares, so a week whose checks
    probe code it never asked for fails there, not in a grading."""

    def declare(probe: Probe) -> Probe:
        probe.exercises = tuple(functions)  # type: ignore[attr-defined]
        return probe

    return declare


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


def robot_for(sub: Any, week: int) -> RobotView:
    """The robot the student's code sees in `week` (the week's QuickBot around the loaded submission)."""
    return RobotView(get_week(week).spec, sub)


def supervisor_for(sub: Any, week: int, start: tuple = (0.0, 0.0, 0.0)) -> tuple[Any, RobotView]:
    """The student's QBSupervisor attached to a fresh robot with its estimate at `start`; both."""
    robot = robot_for(sub, week)
    supervisor = sub.module("qb_supervisor").QBSupervisor()
    supervisor.attach_robot(robot, Pose2D(*start))
    return supervisor, robot
