"""Week 7 probes (run INSIDE the sandbox worker, like grader/inside/probes.py, which lists them): the
sliding test, progress, and the automaton on synthetic events.

Each builds the student's QBSupervisor on a robot whose IR distances the grader chose, puts in what the
grader wants the code to see (the sliding vectors, the goal and d_prog, or every event's value), calls the
student's code once and returns what came back, as plain JSON. It decides nothing.
"""

from __future__ import annotations

from typing import Any

from grader.inside.probing import exercises, plain, supervisor_for

__all__ = ["week7_progress", "week7_progress_point", "week7_sliding", "week7_step"]

EVENTS = ("at_goal", "at_obstacle", "unsafe", "obstacle_cleared", "progress_made", "sliding_left",
          "sliding_right")


def _on_robot(sub, week: int, distances: list, estimate: list | None = None):
    """The student's supervisor with the five IR distances fixed (the conversion is week 2's check)."""
    import numpy as np

    supervisor, robot = supervisor_for(sub, week, tuple(estimate) if estimate else (0.0, 0.0, 0.0))
    values = np.array([float(d) for d in distances])
    setattr(robot, "get_ir_distances", lambda: values.copy())  # noqa: B010 - an instance attribute on purpose
    return supervisor, robot


@exercises("qb_supervisor.py:QBSupervisor.sliding_left", "qb_supervisor.py:QBSupervisor.sliding_right")
def week7_sliding(sub, week: int, direction: str, u_gtg: list, u_ao: list, u_fw: list) -> Any:
    """check_event("sliding_<direction>") with SlidingMode's three vectors replaced by the grader's; the
    event's value and the sigma the provided code kept (sigma_left / sigma_right)."""
    import numpy as np

    supervisor, _ = _on_robot(sub, week, [0.3] * 5)
    vectors = tuple(np.array([float(c) for c in u]) for u in (u_gtg, u_ao, u_fw))
    supervisor.sliding_vectors = lambda side: tuple(v.copy() for v in vectors)
    sliding = supervisor.check_event(f"sliding_{direction}")
    return {"sliding": plain(sliding), "sigma": plain(getattr(supervisor, f"sigma_{direction}", None))}


@exercises("qb_supervisor.py:QBSupervisor.progress_made")
def week7_progress(sub, week: int, goal: list, estimate: list, d_prog: float) -> Any:
    """check_event("progress_made") with the estimate, the goal and d_prog set; also d_prog afterwards."""
    supervisor, _ = _on_robot(sub, week, [0.3] * 5, estimate)
    supervisor.goal = (float(goal[0]), float(goal[1]))
    supervisor.d_prog = float(d_prog)
    made = supervisor.check_event("progress_made")
    return {"progress": plain(made), "d_prog": plain(getattr(supervisor, "d_prog", None))}


@exercises("qb_supervisor.py:QBSupervisor.set_progress_point")
def week7_progress_point(sub, week: int, goal: list, estimate: list, d_prog: float) -> Any:
    """set_progress_point() with the estimate, the goal and d_prog set; d_prog afterwards."""
    supervisor, _ = _on_robot(sub, week, [0.3] * 5, estimate)
    supervisor.goal = (float(goal[0]), float(goal[1]))
    supervisor.d_prog = float(d_prog)
    supervisor.set_progress_point()
    return {"d_prog": plain(getattr(supervisor, "d_prog", None))}


@exercises("qb_supervisor.py:QBSupervisor.execute")
def week7_step(sub, week: int, state: str, fw_direction: str, events: dict, distances: list,
               dt: float = 0.05) -> Any:
    """One QBSupervisor.execute in `state` (with fw_direction set) where check_event(name), and the event's
    own method (self.<name>()), answer `events[name]`: the state afterwards, fw_direction, and the
    direction FollowWall was run with (None when another controller ran)."""
    supervisor, _ = _on_robot(sub, week, distances)
    supervisor.switch_to_state(state)
    supervisor.fw_direction = fw_direction
    supervisor.events = {name: (lambda value=bool(events[name]): value) for name in EVENTS}
    # An automaton may read an event by calling its method (self.progress_made()) as well as through
    # check_event: both must answer the grader's value, or a right automaton is judged on events it
    # computed itself (issue 21).
    for name, answer in supervisor.events.items():
        setattr(supervisor, name, answer)
    follow_wall = supervisor.controllers.get("follow_wall")
    seen: dict[str, Any] = {}
    if follow_wall is not None:
        run = follow_wall.execute

        def recorded(robot, state_estimate, inputs, dt):
            seen["direction"] = getattr(inputs, "direction", None)
            return run(robot, state_estimate, inputs, dt)

        follow_wall.execute = recorded
    supervisor.execute(dt)
    return {
        "state": plain(supervisor.current_state),
        "fw_direction": plain(getattr(supervisor, "fw_direction", None)),
        "follow_wall_direction": plain(seen.get("direction")),
    }

