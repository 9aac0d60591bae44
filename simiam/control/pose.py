"""Pose2D: a planar pose (x, y, theta), as the original's simiam.ui.Pose2D."""

from __future__ import annotations

import math


class Pose2D:
    """A pose in the plane: position (x, y) in metres and heading theta in radians.

    `unpack()` returns `(x, y, theta)` as in the manual's `[x, y, theta] = pose.unpack()`.
    """

    __slots__ = ("x", "y", "theta")

    def __init__(self, x: float = 0.0, y: float = 0.0, theta: float = 0.0) -> None:
        self.x = x
        self.y = y
        self.theta = theta

    def unpack(self) -> tuple[float, float, float]:
        """Return (x, y, theta)."""
        return self.x, self.y, self.theta

    def set_pose(self, pose) -> None:
        """Set (x, y, theta) from any 3-sequence, like the original's `set_pose([x, y, theta])`."""
        self.x, self.y, self.theta = pose

    def transformation_matrix(self) -> list[list[float]]:
        """The 3x3 homogeneous transform T(x, y, theta) of this pose."""
        c, s = math.cos(self.theta), math.sin(self.theta)
        return [[c, -s, self.x], [s, c, self.y], [0.0, 0.0, 1.0]]

    def __iter__(self):
        return iter((self.x, self.y, self.theta))

    def __repr__(self) -> str:
        return f"Pose2D(x={self.x!r}, y={self.y!r}, theta={self.theta!r})"
