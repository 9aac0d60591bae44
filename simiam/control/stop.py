"""The provided Stop controller: v = w = 0."""

from __future__ import annotations

from simiam.control.controller import Controller, Inputs
from simiam.control.pose import Pose2D


class Stop(Controller):
    """Stops the robot (state "stop")."""

    def __init__(self) -> None:
        super().__init__("stop")

    def execute(self, robot, state_estimate: Pose2D, inputs: Inputs, dt: float) -> tuple[float, float]:
        """Return (0, 0)."""
        return 0.0, 0.0
