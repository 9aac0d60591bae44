"""Worlds: obstacles, goal and start poses, read from the original's settings.xml format."""

from simiam.world.settings_xml import WorldFileError, load_world, world_path
from simiam.world.world import World

__all__ = ["World", "WorldFileError", "load_world", "world_path"]
