"""GoToAngle (provided): a P regulator that steers the robot to the heading theta_d at speed v.

Nothing to write here. Uncomment the print lines to watch your IR distances (week 2, part 3).
"""

import math

from simiam.control import Controller


class GoToAngle(Controller):
    """Steers to inputs.theta_d: w = Kp * (theta_d - theta), the error wrapped into [-pi, pi]."""

    def __init__(self):
        super().__init__("go_to_angle")
        self.Kp = 1

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w): drive at inputs.v and turn toward inputs.theta_d."""
        x, y, theta = state_estimate.unpack()
        theta_d = inputs.theta_d

        ir_distances = robot.get_ir_distances()
        # for i, d in enumerate(ir_distances):
        #     print(f"IR {i + 1}: {d:0.3f}m")

        e_k = theta_d - theta
        e_k = math.atan2(math.sin(e_k), math.cos(e_k))
        w = self.Kp * e_k

        self.theta_g = theta_d
        self.ir_distances = ir_distances
        return inputs.v, w
