"""Week 3's probes: ensure_w and GoToGoal. They run INSIDE the sandbox worker against the student's loaded
code (grader/inside/probes.py lists them), call it with the inputs the grader chose and return what came
back as plain JSON; they decide nothing."""

from __future__ import annotations

from typing import Any

from grader.inside.probing import exercises, plain, robot_for, supervisor_for
from simiam.control.controller import Inputs
from simiam.control.pose import Pose2D

__all__ = ["ensure_w", "go_to_goal"]


@exercises("qb_supervisor.py:QBSupervisor.ensure_w")
def ensure_w(sub, week: int, v: float, w: float) -> Any:
    """QBSupervisor.ensure_w(robot, v, w) -> (vel_r, vel_l)."""
    supervisor, robot = supervisor_for(sub, week)
    return plain(supervisor.ensure_w(robot, v, w))


_GAINS = ("Kp", "Ki", "Kd")


def _pinned(cls):
    """The student's controller class with its gains pinned once the grader has set them: a write to
    Kp/Ki/Kd inside execute is recorded in `_grader_overwrote` and ignored, so the terms are still checked
    with the grader's gains and the overwrite is reported once (week3.pid.memory), not as wrong arithmetic."""

    class Pinned(cls):
        def __setattr__(self, name, value):
            if name in _GAINS and self.__dict__.get("_grader_pin"):
                self.__dict__["_grader_overwrote"][name] = value
                return
            super().__setattr__(name, value)

    Pinned.__name__ = cls.__name__
    return Pinned


@exercises("go_to_goal.py:GoToGoal.execute")
def go_to_goal(sub, week: int, gains: dict, calls: list, fresh: bool = False) -> Any:
    """GoToGoal.execute for a sequence of calls [{"pose": [x, y, theta], "goal": [x, y], "v": v, "dt": dt,
    "memory": {"E_k": .., "e_k_1": ..} (optional, set before the call)}].

    With `fresh` every call gets a new controller (no memory); otherwise one controller sees them all.
    Returns per call {"out": (v, w), "theta_g", "e_k" and "E_k" (what the controller stored for the next
    call: the provided code keeps e_k in e_k_1 and e_I in E_k), "overwrote": gains execute tried to set}.
    """
    robot = robot_for(sub, week)
    cls = sub.module("go_to_goal").GoToGoal
    pinned = _pinned(cls) if "__slots__" not in vars(cls) else cls
    ctrl = None
    out = []
    for call in calls:
        if ctrl is None or fresh:
            ctrl = pinned()
            for name, value in gains.items():
                setattr(ctrl, name, value)
            if hasattr(ctrl, "__dict__"):
                ctrl.__dict__["_grader_overwrote"] = {}
                ctrl.__dict__["_grader_pin"] = True
        for name, value in (call.get("memory") or {}).items():
            if name in ("E_k", "e_k_1"):
                setattr(ctrl, name, value)
        x_g, y_g = call["goal"]
        inputs = Inputs(v=call["v"], x_g=x_g, y_g=y_g, theta_d=0.0)
        result = ctrl.execute(robot, Pose2D(*call["pose"]), inputs, call["dt"])
        overwrote = getattr(ctrl, "__dict__", {}).get("_grader_overwrote", {})
        out.append(
            {
                "out": plain(result),
                "theta_g": plain(getattr(ctrl, "theta_g", None)),
                "e_k": plain(getattr(ctrl, "e_k_1", None)),
                "E_k": plain(getattr(ctrl, "E_k", None)),
                "overwrote": {k: plain(v) for k, v in overwrote.items() if k in _GAINS},
            }
        )
    return out
