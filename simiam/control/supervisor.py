"""Supervisor base class: the state estimate, the controllers, switching between them, events.

The student's `QBSupervisor` (qb_supervisor.py) derives from this and writes `execute(dt)`,
`update_odometry()` and (week 3) `ensure_w(robot, v, w)`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from simiam.control.controller import Controller, Inputs
from simiam.control.pose import Pose2D


@dataclass
class WheelTicks:
    """Encoder ticks remembered from the last odometry update (`prev_ticks.right`, `prev_ticks.left`)."""

    right: int = 0
    left: int = 0


class Supervisor:
    """Holds the controllers and decides which one runs (the original's QBSupervisor skeleton).

    Attributes a student uses: `robot` (the RobotView), `state_estimate` (a Pose2D from odometry),
    `prev_ticks`, `controllers` (state name -> Controller), `current_controller`, `current_state`,
    and the week's settings `v`, `theta_d`, `goal`, `d_stop`, and (week 6 on) `d_fw`, `fw_direction`.
    """

    def __init__(self) -> None:
        self.robot = None
        self.state_estimate = Pose2D(0.0, 0.0, 0.0)
        self.prev_ticks = WheelTicks(0, 0)
        self.controllers: dict[str, Controller] = {}
        self.current_controller: Controller | None = None
        self.current_state: str | None = None
        self.v = 0.0
        self.theta_d = 0.0
        self.goal = (0.0, 0.0)
        self.d_stop = 0.05
        # follow-wall (week 6 on): the distance to keep from the wall and its side, "left" or "right"
        self.d_fw = 0.15
        self.fw_direction = "left"
        # limits of the unicycle model, set by attach_robot as in the original
        self.v_max_w0 = 0.0
        self.w_max_v0 = 0.0
        self.v_min_w0 = 0.0
        self.w_min_v0 = 0.0
        # the last (v, w) a controller returned, before ensure_w (plotted by the viewer)
        self.outputs: tuple[float, float] | None = None
        self.events = {"at_goal": self.at_goal}

    # -- controllers and states -------------------------------------------------------------
    def add_controller(self, controller: Controller) -> Controller:
        """Register a controller under its state name (its `type`); return it."""
        self.controllers[controller.type] = controller
        return controller

    def switch_to_state(self, name: str) -> None:
        """Make the controller called `name` the current one (nothing happens if it already is)."""
        if name == self.current_state:
            return
        if name not in self.controllers:
            raise ValueError(f"no state exists with name {name!r} (states: {', '.join(self.controllers)})")
        self.current_controller = self.controllers[name]
        self.current_state = name

    def check_event(self, name: str) -> bool:
        """Evaluate the event called `name` (e.g. "at_goal")."""
        if name not in self.events:
            raise ValueError(f"no event exists with name {name!r}")
        return bool(self.events[name]())

    def at_goal(self) -> bool:
        """True when the *estimated* position is closer than d_stop to the goal."""
        x, y, _ = self.state_estimate.unpack()
        return math.hypot(x - self.goal[0], y - self.goal[1]) < self.d_stop

    def inputs(self) -> Inputs:
        """The inputs every controller gets: v, the goal (x_g, y_g), theta_d, direction (= fw_direction)
        and d_fw."""
        return Inputs(v=self.v, x_g=self.goal[0], y_g=self.goal[1], theta_d=self.theta_d,
                      direction=self.fw_direction, d_fw=self.d_fw)

    def execute_controller(self, inputs: Inputs, dt: float) -> tuple[float, float]:
        """Run the current controller and return its (v, w); remembered in `self.outputs` for plots."""
        if self.current_controller is None:
            raise ValueError("no controller is running: call self.switch_to_state(name) in __init__ first")
        v, w = self.current_controller.execute(self.robot, self.state_estimate, inputs, dt)
        self.outputs = (v, w)
        return v, w

    # -- the robot ------------------------------------------------------------------------------
    def attach_robot(self, robot, pose: Pose2D) -> None:
        """Attach the robot and start the estimate at `pose`; derive the unicycle limits."""
        self.robot = robot
        self.state_estimate.set_pose(pose.unpack())
        dyn = robot.dynamics
        _, self.w_max_v0 = dyn.diff_to_uni(robot, robot.max_vel, -robot.max_vel)
        self.v_max_w0, _ = dyn.diff_to_uni(robot, robot.max_vel, robot.max_vel)
        _, self.w_min_v0 = dyn.diff_to_uni(robot, robot.min_vel, -robot.min_vel)
        self.v_min_w0, _ = dyn.diff_to_uni(robot, robot.min_vel, robot.min_vel)

    def execute(self, dt: float) -> None:
        """One control step: the student's QBSupervisor defines it."""
        raise NotImplementedError("QBSupervisor must define execute(self, dt)")
