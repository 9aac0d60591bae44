"""Probes: small functions that run INSIDE the sandbox worker against the student's loaded code.

The worker answers `{"op": "probe", "name": ..., "args": {...}}` with `dispatch(sub, name, args)`, where
`sub` is the loaded submission (`simiam.course.loader.Submission`). A probe calls the student's functions
with the inputs the grader chose and returns what came back as plain JSON. It decides nothing: everything
it returns is untrusted, and the grading process validates and scores it (grader/checks/).

This module is the registry only: each week's probes live in grader/inside/probes_weekN.py (what they
share, in grader/inside/probing.py), and every probe takes `week` so it can build the robot the student
code sees. tests/course/test_week_parts.py checks that every probe here is named by some week's checks
and every probe a check names is here.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from grader.inside.probes_week2 import ir_distances, odometry, uni_to_diff
from grader.inside.probes_week3 import ensure_w, go_to_goal
from grader.inside.probes_week4 import avoid_obstacles, sensor_geometry, transformation_matrix
from grader.inside.probes_week5 import blend, switching
from grader.inside.probes_week6 import follow_wall, wall_settings
from grader.inside.probes_week7 import week7_progress, week7_progress_point, week7_sliding, week7_step

PROBES: dict[str, Callable[..., Any]] = {
    "uni_to_diff": uni_to_diff,
    "odometry": odometry,
    "ir_distances": ir_distances,
    "ensure_w": ensure_w,
    "go_to_goal": go_to_goal,
    "transformation_matrix": transformation_matrix,
    "sensor_geometry": sensor_geometry,
    "avoid_obstacles": avoid_obstacles,
    "blend": blend,
    "switching": switching,
    "follow_wall": follow_wall,
    "wall_settings": wall_settings,
    "week7_sliding": week7_sliding,
    "week7_progress": week7_progress,
    "week7_progress_point": week7_progress_point,
    "week7_step": week7_step,
}
__all__ = sorted(PROBES)  # the worker's allow-list (worker_loop._probe_names): the probes, nothing else


def dispatch(sub, name: str, args: dict) -> Any:
    """Run probe `name` with `args` (the worker's entry point); KeyError for an unknown probe."""
    if name not in PROBES:
        raise KeyError(f"no probe named {name!r}")
    return PROBES[name](sub, **args)
