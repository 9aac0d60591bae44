"""grader.scenarios.min_clearance as it was before issue 24 (f3ce8ef), verbatim, on the clearance module
kept next to it: the reference tests/grader/test_same_after_issue24.py compares the culled one against."""

from __future__ import annotations

import math

from grader import reference as ref

import clearance  # noqa: I001  (the copy in this folder, put on sys.path by the test)


def min_clearance(trace, world, spec, every: int = 1) -> float | None:
    """The smallest gap (m) between the robot's base plate and any obstacle, at every `every`-th step
    (and the last); 0 once they touch. None for a world without obstacles. Every step by default: it is
    the figure the collision margins are read from (grader.margins), and a step moves the robot up to
    7.5 mm, so sampling fewer steps could overstate a margin by more than that (about 20 ms a 90 s run)."""
    if not world.obstacles:
        return None
    obstacles = [clearance.Shape(p) for p in world.obstacles]
    plate = spec.base_plate
    s = trace.steps
    rows = list(range(0, len(s["x"]), every)) + [len(s["x"]) - 1]
    gap = math.inf
    for k in rows:
        x, y, th = s["x"][k], s["y"][k], s["theta"][k]
        body = clearance.Shape(ref.placed((x, y, th), plate))
        for obstacle in obstacles:
            if clearance.box_gap(body.box, obstacle.box) < gap:  # else it cannot be the nearest
                gap = clearance.nearer(body, obstacle, gap)
    return gap
