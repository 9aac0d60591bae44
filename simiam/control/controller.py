"""Controller base class and the Inputs a supervisor hands to every controller."""

from __future__ import annotations

from dataclasses import dataclass

from simiam.control.pose import Pose2D

# the sides FollowWall can follow a wall on; "" is what the week-7 supervisor sets after leaving a wall
DIRECTIONS = ("left", "right", "")


@dataclass
class Inputs:
    """What a supervisor passes to a controller each step (the original's `inputs` struct).

    `v`: linear velocity (m/s); `x_g`, `y_g`: the goal; `theta_d`: the desired heading (go-to-angle);
    `direction`: the side of the wall to follow, "left" or "right" ("" counts as "left", as in the original);
    `d_fw`: the distance (m) to keep from the wall (follow-wall, week 6 on).
    """

    v: float = 0.0
    x_g: float = 0.0
    y_g: float = 0.0
    theta_d: float = 0.0
    direction: str = "left"
    d_fw: float = 0.15

    def __post_init__(self) -> None:
        # The original compared the direction with 'right' and took anything else for left, so a typo
        # ("rigth", "Right") silently followed the wrong wall; here it is an error that names the value.
        if self.direction not in DIRECTIONS:
            raise ValueError(f"the wall-following direction must be 'left' or 'right', got {self.direction!r}"
                             " (set fw_direction in QBSupervisor.__init__)")


class Controller:
    """Base of every controller.

    A controller has a `type` (the state name a supervisor switches to, e.g. "go_to_goal") and
    `execute(robot, state_estimate, inputs, dt) -> (v, w)`. PID controllers keep their memory in
    `E_k` (accumulated error) and `e_k_1` (previous error); `reset()` zeroes it.

    After computing, a controller stores what the viewer and the grader plot: `theta_g` (its reference
    heading), `u_ao` (avoid-obstacles vector), `ir_distances_wf` (IR points in the world frame), and
    from week 5 `u_gtg` (go-to-goal vector) and `u_ao_gtg` (the blend of the two).
    They stay None for controllers that have no such quantity.
    """

    def __init__(self, type_name: str) -> None:
        self.type = type_name
        self.E_k = 0.0
        self.e_k_1 = 0.0
        self.theta_g: float | None = None
        self.u_ao = None
        self.ir_distances_wf = None
        self.u_gtg = None
        self.u_ao_gtg = None

    def execute(self, robot, state_estimate: Pose2D, inputs: Inputs, dt: float) -> tuple[float, float]:
        """Compute (v, w) from the robot's sensors and the state estimate."""
        raise NotImplementedError(f"controller {self.type!r} has no execute()")

    def reset(self) -> None:
        """Forget the accumulated and the previous error."""
        self.E_k = 0.0
        self.e_k_1 = 0.0
