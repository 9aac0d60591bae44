"""What each week of the course sets: robot, world, student files, supervisor settings, scenario length.

`week_config(n)` returns the WeekConfig of week n (1..4). `default_settings` are the course's own values
(the ones the solutions' QBSupervisor.__init__ sets); a run passes them to LocalBrain only when it wants
to override what the student's code sets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from simiam.robot.quickbot import RobotSpec

_COMMON = ("differential_drive.py", "quickbot.py", "go_to_angle.py", "qb_supervisor.py")


@dataclass(frozen=True)
class WeekConfig:
    """One week: `number`, `world` (packaged world name), `student_files` (import order),
    `required_names` (file -> names it must define), `default_settings`, `seconds` (scenario length),
    `start` pose, `dt` (default time step). `spec` is the week's RobotSpec."""

    number: int
    world: str
    student_files: tuple[str, ...]
    required_names: dict[str, tuple[str, ...]]
    default_settings: dict = field(default_factory=dict)
    seconds: float = 10.0
    start: tuple[float, float, float] = (0.0, 0.0, 0.0)
    dt: float = 0.033

    @property
    def name(self) -> str:
        """"week1" .. "week4": the folder name under assignments/ and solutions/."""
        return f"week{self.number}"

    @property
    def spec(self) -> RobotSpec:
        """The week's RobotSpec (R, L, ticks/rev, max_vel, min_vel, IR mode, mounts)."""
        from simiam.robot.quickbot import spec_for_week

        return spec_for_week(self.number)


_DRIVE = {"differential_drive.py": ("uni_to_diff", "diff_to_uni")}
_IR = {"quickbot.py": ("get_ir_distances",)}
_ANGLE = {"go_to_angle.py": ("GoToAngle",)}
_SUPERVISOR = ("QBSupervisor", "QBSupervisor.execute", "QBSupervisor.update_odometry")

WEEKS: dict[int, WeekConfig] = {
    1: WeekConfig(
        number=1,
        world="week1",
        student_files=("differential_drive.py", "quickbot.py", "qb_supervisor.py"),
        required_names={**_DRIVE, **_IR, "qb_supervisor.py": _SUPERVISOR},
        default_settings={},
        seconds=5.0,
    ),
    2: WeekConfig(
        number=2,
        world="week2",
        student_files=_COMMON,
        required_names={**_DRIVE, **_IR, **_ANGLE, "qb_supervisor.py": _SUPERVISOR},
        default_settings={"theta_d": math.pi / 4, "v": 0.1},
        seconds=10.0,
    ),
    3: WeekConfig(
        number=3,
        world="week3",
        student_files=_COMMON[:3] + ("go_to_goal.py", "qb_supervisor.py"),
        required_names={
            **_DRIVE,
            **_IR,
            **_ANGLE,
            "go_to_goal.py": ("GoToGoal", "GoToGoal.execute"),
            "qb_supervisor.py": _SUPERVISOR + ("QBSupervisor.ensure_w",),
        },
        default_settings={"v": 0.2, "goal": (-1.0, 1.0), "d_stop": 0.05},
        seconds=30.0,
    ),
    4: WeekConfig(
        number=4,
        world="week4",
        student_files=_COMMON[:3] + ("go_to_goal.py", "avoid_obstacles.py", "qb_supervisor.py"),
        required_names={
            **_DRIVE,
            **_IR,
            **_ANGLE,
            "go_to_goal.py": ("GoToGoal", "GoToGoal.execute"),
            "avoid_obstacles.py": (
                "AvoidObstacles",
                "AvoidObstacles.execute",
                "AvoidObstacles.apply_sensor_geometry",
                "AvoidObstacles.get_transformation_matrix",
            ),
            "qb_supervisor.py": _SUPERVISOR + ("QBSupervisor.ensure_w",),
        },
        default_settings={"v": 0.15, "goal": (-1.0, 1.0), "d_stop": 0.05, "state": "avoid_obstacles"},
        seconds=60.0,
    ),
}


def week_config(week: int | str) -> WeekConfig:
    """The WeekConfig of week 1..4 (an int, "3" or "week3")."""
    text = str(week).strip().lower().removeprefix("week")
    if not text.isdigit() or int(text) not in WEEKS:
        raise ValueError(f"no such week: {week!r} (weeks 1 to 4)")
    return WEEKS[int(text)]
