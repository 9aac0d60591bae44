"""Week 5's probes (they run INSIDE the worker and import nothing trusted; grader/inside/probes.py lists
them with the other weeks').

- `blend`: AOandGTG.execute with u_ao and u_gtg chosen by the grader: the controller's AvoidObstacles is
  replaced by one that hands over the grader's u_ao, and the goal sets u_gtg. What comes back is the
  student's u_ao_gtg (and the vectors the block was given), so a week-4 mistake cannot change the blend.
- `switching`: one QBSupervisor.execute with is_blending off, from a chosen state, with chosen IR
  distances and the estimate at or away from the goal; the state the block picked and the switch count.
"""

from __future__ import annotations

from typing import Any

from grader.inside.probing import exercises, plain, robot_for
from simiam.control.controller import Inputs
from simiam.control.pose import Pose2D
from simiam.control.robot_view import RobotView


class _GivenAvoid:
    """Stands in for AOandGTG's AvoidObstacles: u_ao is what the grader chose."""

    def __init__(self, u_ao: list[float]) -> None:
        self.u_ao = list(u_ao)
        self.ir_distances_wf = None

    def execute(self, robot, state_estimate, inputs, dt):
        return inputs.v, 0.0


def _robot(sub, week: int, distances: list[float]) -> RobotView:
    robot = robot_for(sub, week)
    setattr(robot, "get_ir_distances", lambda: list(distances))  # noqa: B010 - the conversion is week 2's
    return robot


@exercises("ao_and_gtg.py:AOandGTG.execute")
def blend(sub, week: int, calls: list[dict]) -> list[dict[str, Any]]:
    """For each call {"u_ao": [x, y], "pose": [x, y, theta], "goal": [x, y]}: a fresh AOandGTG's execute
    with that u_ao (u_gtg = goal - position). Returns per call the blend u_ao_gtg, the heading theta_g and
    the u_gtg/u_ao the controller kept."""
    out = []
    cls = sub.module("ao_and_gtg").AOandGTG
    for call in calls:
        ctrl = cls()
        ctrl.avoid = _GivenAvoid(call["u_ao"])
        x_g, y_g = call["goal"]
        result = ctrl.execute(_robot(sub, week, [0.3] * 5), Pose2D(*call["pose"]),
                              Inputs(v=0.15, x_g=x_g, y_g=y_g, theta_d=0.0), 0.05)
        out.append({
            "out": plain(result),
            "u_ao_gtg": plain(getattr(ctrl, "u_ao_gtg", None)),
            "theta_g": plain(getattr(ctrl, "theta_g", None)),
        })
    return out


@exercises("qb_supervisor.py:QBSupervisor.execute")
def switching(sub, week: int, cases: list[dict]) -> list[dict[str, Any]]:
    """For each case {"state": first state, "distances": [5 IR distances], "at_goal": bool}: a fresh
    QBSupervisor (is_blending off, the goal at the estimate's start or 1 m away), switched to `state`, then
    one execute. Returns per case the state it ended in, how many switches it counted (switch_count), how
    many happened (switches_seen: also a controller changed around switch_to_state) and the states switched
    into, in order."""
    out = []
    for case in cases:
        robot = _robot(sub, week, case["distances"])
        supervisor = sub.module("qb_supervisor").QBSupervisor()
        supervisor.attach_robot(robot, Pose2D(0.0, 0.0, 0.0))
        supervisor.is_blending = False
        supervisor.goal = (0.0, 0.0) if case["at_goal"] else (1.0, 0.0)
        supervisor.switch_to_state(case["state"])
        supervisor.settle()
        before, seen = supervisor.switch_count, supervisor.switches_seen
        supervisor.execute(0.05)
        out.append({"state": plain(supervisor.current_state),
                    "switches": plain(supervisor.switch_count - before),
                    "seen": plain(supervisor.switches_seen - seen),
                    "path": [plain(p) for p in supervisor.switched_into]})
    return out


