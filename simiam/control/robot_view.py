"""RobotView: the robot as student code sees it (the contract's names), never the true pose.

It is fed each step with plain readings (ticks, raw IR values) and records the wheel speeds the
supervisor asks for; the trusted simulator applies the motor limits afterwards.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from simiam.control.pose import Pose2D


class WheelEncoder:
    """One wheel encoder: `ticks` (cumulative) and `ticks_per_rev`."""

    def __init__(self, ticks_per_rev: int) -> None:
        self.ticks = 0
        self.ticks_per_rev = ticks_per_rev


class IRSensor:
    """One IR sensor: `get_range()` is the raw ADC value; `location` is the mount pose in the robot frame."""

    def __init__(self, location: Pose2D) -> None:
        self.location = location
        self._raw = 0

    def get_range(self) -> int:
        """The raw ADC value of this sensor (not metres: convert with get_ir_distances)."""
        return self._raw


class RobotView:
    """The QuickBot handed to the supervisor and the controllers.

    `wheel_radius`, `wheel_base_length`, `max_vel`, `min_vel`; `encoders[0]` right, `encoders[1]` left;
    `ir_array[0..4]` (the manual's sensors 1..5); `get_ir_distances()` through the student's
    quickbot.get_ir_distances; `set_wheel_speeds(vel_r, vel_l)`; `dynamics.uni_to_diff(robot, v, w)`
    and `dynamics.diff_to_uni(robot, vel_r, vel_l)` (the student's differential_drive module).
    """

    def __init__(self, spec, submission) -> None:
        self.wheel_radius: float = spec.wheel_radius
        self.wheel_base_length: float = spec.wheel_base_length
        self.max_vel: float = spec.max_vel
        self.min_vel: float = spec.min_vel
        self.encoders = [WheelEncoder(spec.ticks_per_rev), WheelEncoder(spec.ticks_per_rev)]
        self.ir_array = [IRSensor(Pose2D(*mount)) for mount in spec.ir_mounts]
        self.dynamics = submission.modules.get("differential_drive")
        self._quickbot = submission.modules.get("quickbot")
        # the last request of set_wheel_speeds (rad/s), before the simulator's limits
        self.vel_r = 0.0
        self.vel_l = 0.0

    def update(self, readings: Mapping[str, Any]) -> None:
        """Take one step's readings: {"ticks": [right, left], "ir_raw": [one int per IR sensor], ...}."""
        self.encoders[0].ticks, self.encoders[1].ticks = readings["ticks"]
        for sensor, raw in zip(self.ir_array, readings["ir_raw"], strict=True):
            sensor._raw = raw

    def get_ir_distances(self):
        """The five IR distances in metres, through quickbot.get_ir_distances(robot)."""
        if self._quickbot is None:
            raise RuntimeError("this week's code has no quickbot.py, so IR distances are not available")
        return self._quickbot.get_ir_distances(self)

    def set_wheel_speeds(self, vel_r: float, vel_l: float) -> None:
        """Ask for wheel angular speeds (rad/s); the robot applies its motor limits."""
        self.vel_r = vel_r
        self.vel_l = vel_l
