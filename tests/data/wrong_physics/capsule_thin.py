"""WRONG cone cull: each IR cone's capsule is its axis alone (the apex-to-tip segment, no width), so a cone
whose far points reach an obstacle beside the axis is never placed and reads max_range."""
from simiam.physics.robot_surfaces import RobotSurfaces


def thin(surfaces: RobotSurfaces) -> RobotSurfaces:
    surfaces._capsules = [(ax, ay, tx, ty, 0.0) for ax, ay, tx, ty, _ in surfaces._capsules]
    return surfaces
