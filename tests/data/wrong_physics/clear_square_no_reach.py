"""WRONG clear square: the clearance is measured from the body origin to the obstacles' boxes, forgetting
that the IR cones reach 0.37 m beyond it, so a robot driving at a wall reads max_range until its origin
is nearly at the wall."""
import math


def _clearance(self, x, y):
    return min((max(p[0] - x, x - p[1], p[2] - y, y - p[3]) for p in self.obstacles.polygons),
               default=math.inf) - 1e-9


def install(monkeypatch) -> None:
    from simiam.physics.robot_surfaces import RobotSurfaces

    monkeypatch.setattr(RobotSurfaces, "_clearance", _clearance)
