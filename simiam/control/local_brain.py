"""LocalBrain: runs a loaded submission in this process (simiam run, fidelity tests, the sandbox worker).

Implements the simulator's Brain seam: `step(readings) -> command` with plain values only.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from simiam.control.pose import Pose2D
from simiam.control.robot_view import RobotView
from simiam.course.week import EXTRA_SETTINGS, NAMED_SETTINGS, check_setting_names, unknown_setting
from simiam.signals import declared, read_plan, read_signals, week_signals
from simiam.signals import plain as _plain

if TYPE_CHECKING:
    from simiam.course.week import Week

# settings that are not plain attributes of the supervisor (every other one is, e.g. v, goal, d_fw)
_NOT_ATTRIBUTES = ("state", "gains", "estimate")


class LocalBrain:
    """Builds a RobotView and the student's QBSupervisor and steps them with the simulator's readings.

    `settings` overrides what the student's QBSupervisor.__init__ set: `v`, `goal` (x, y), `d_stop`,
    `theta_d` and any other supervisor attribute a week declares (`SupervisorSettings.extra`: week 5's
    `d_at_obs`, `d_unsafe`, `is_blending`, week 6's `d_fw`, `fw_direction`), the initial `state` (a
    controller name such as "go_to_goal"), and controller gains as
    `{"gains": {"go_to_goal": {"Kp": 4, "Ki": 0.01, "Kd": 0.01}}}` (a top-level
    `{"go_to_goal": {...}}` is accepted too). `start` is where the estimate starts (default: the week's);
    the setting `estimate` (x, y, theta) moves it there too, as the original's week-6 tests set it.
    A setting of another name (or a gain the controller does not have) is refused with a ValueError that
    names it and the known names, closest first: a misspelt one would be set and never read.
    The debug values are the week's declared signals (`week.debug_signals`, else weeks 1-4's), read from
    the supervisor and its current controller by simiam.signals.read_signals.
    """

    def __init__(self, submission, week: Week, settings: dict | None = None,
                 start: tuple[float, float, float] | None = None) -> None:
        self.week = week
        self.signals = declared(week_signals(week))
        self._n_ir = len(week.spec.ir_mounts)
        self._plan = read_plan(self.signals, self._n_ir)
        self.robot = RobotView(week.spec, submission)
        supervisor_class = submission.module("qb_supervisor").QBSupervisor
        self.supervisor = supervisor_class()
        self.supervisor.attach_robot(self.robot, Pose2D(*(start or week.start)))
        self.apply_settings(settings or {})
        self.supervisor.settle()      # the run's switches are counted from the state it starts in

    def apply_settings(self, settings: dict) -> None:
        """Override the supervisor's settings and controller gains (see the class docstring)."""
        sup = self.supervisor
        check_setting_names(settings, NAMED_SETTINGS + EXTRA_SETTINGS + tuple(sup.controllers),
                            "the settings of this run")
        for key, value in settings.items():
            if key not in _NOT_ATTRIBUTES and key not in sup.controllers:
                setattr(sup, key, tuple(value) if key == "goal" else value)
        gains = dict(settings.get("gains") or {})
        gains.update({k: v for k, v in settings.items() if k in sup.controllers and isinstance(v, dict)})
        for name, values in gains.items():
            if name not in sup.controllers:
                have = ", ".join(sup.controllers)
                raise ValueError(f"no controller {name!r} to set gains on (have: {have})")
            controller = sup.controllers[name]
            for gain, value in values.items():
                if not isinstance(gain, str) or not hasattr(controller, gain):
                    numbers = [k for k, v in vars(controller).items()
                               if isinstance(v, (int, float)) and not isinstance(v, bool)]
                    raise unknown_setting(gain, numbers, f"the gains of {name}", kind="gain")
                setattr(controller, gain, value)
        if settings.get("state"):
            sup.switch_to_state(settings["state"])
        if settings.get("estimate") is not None:
            pose = settings["estimate"]
            if not (isinstance(pose, (list, tuple)) and len(pose) == 3
                    and all(isinstance(c, (int, float)) and math.isfinite(c) for c in pose)):
                raise ValueError(f"the setting estimate must be three finite numbers (x, y, theta), "
                                 f"got {pose!r}")
            sup.state_estimate.set_pose(tuple(float(c) for c in pose))

    def step(self, readings: Mapping[str, Any]) -> dict[str, Any]:
        """Feed one step's readings to the robot, run the supervisor once, return the command
        (simiam.brain's Readings and Command; not imported here, the worker has no simiam.brain)."""
        self.think(readings)
        return self.answer()

    def think(self, readings: Mapping[str, Any]) -> None:
        """The first half of `step`: feed the readings to the robot and run the supervisor once."""
        self.robot.update(readings)
        sup = self.supervisor
        sup.outputs = None
        sup.event_values = {}
        sup.execute(readings["dt"])

    def answer(self) -> dict[str, Any]:
        """The second half of `step`: the command, read from the robot and the supervisor as they are now
        (in this order: the wheel speeds, the estimate, the state, the debug signals). The sandbox's worker
        reads the same, in the same order, straight into its step record (grader.inside.record_writer)."""
        sup = self.supervisor
        return {
            "vel_r": _plain(self.robot.vel_r),
            "vel_l": _plain(self.robot.vel_l),
            "estimate": [_plain(c) for c in sup.state_estimate.unpack()],
            "state": str(sup.current_state),
            "debug": read_signals(sup, self.signals, self._n_ir, self._plan),
        }

