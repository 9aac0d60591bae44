"""`World`: the arena the robot drives in. Obstacles are polygons in world coordinates (the original's
`Obstacle` surfaces after `T(pose)` was applied), plus an optional goal and the robot start pose(s)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

Pose = tuple[float, float, float]


@dataclass
class World:
    """Named obstacles (each an (n, 2) float array of world-frame vertices, closed implicitly),
    robot start poses (x, y, theta), and an optional goal (x, y).

    Build one from code (`World("mine", [np.array([[0, 0], [1, 0], [1, 1]])])`) or from a settings.xml
    file with `simiam.world.load_world`.
    """

    name: str
    obstacles: list[np.ndarray] = field(default_factory=list)
    starts: list[Pose] = field(default_factory=lambda: [(0.0, 0.0, 0.0)])
    goal: tuple[float, float] | None = None
    source: Path | None = None

    def __post_init__(self) -> None:
        polys = []
        for i, poly in enumerate(self.obstacles):
            a = np.array(poly, dtype=float)
            if a.ndim != 2 or a.shape[1] != 2 or a.shape[0] < 3:
                raise ValueError(f"obstacle {i + 1} of world {self.name!r} must be at least 3 (x, y) points")
            polys.append(a)
        self.obstacles = polys
        self.starts = [tuple(float(c) for c in s) for s in self.starts]  # type: ignore[misc]

    @property
    def start(self) -> Pose:
        """The first robot's start pose."""
        return self.starts[0] if self.starts else (0.0, 0.0, 0.0)

    def to_json(self) -> dict:
        """The trace's `world` object: name and obstacle vertices as plain lists."""
        return {"name": self.name, "obstacles": [p.tolist() for p in self.obstacles]}
