"""GoToGoal: a PID regulator that steers the robot to the goal (x_g, y_g) at a constant speed v.

Student blocks (week 3, shipped filled in from week 4) and the placeholders the stub would get:
  part 1, the heading to the goal (1st block of execute): `u_x = 0`, `u_y = 0`, `theta_g = 0`.
  part 2, the heading error wrapped into [-pi, pi] (2nd block of execute): `e_k = 0`.
  part 3, the PID terms (3rd block of execute): `e_P = 0`, `e_I = 0`, `e_D = 0`.
  part 3, the __init__ gains: `self.Kp = 0`, `self.Ki = 0`, `self.Kd = 0` (tune them: theta settles
     within 10% in 3 s or less, with at most 10% overshoot). Part 4, ensure_w, is in qb_supervisor.py.
With the placeholders the robot drives straight ahead.
"""

import math

from simiam.control import Controller


class GoToGoal(Controller):
    """Steers toward inputs.x_g, inputs.y_g with w = Kp*e_P + Ki*e_I + Kd*e_D; v = inputs.v."""

    def __init__(self):
        super().__init__("go_to_goal")

        # gains of the PID regulator
        # START CODE BLOCK
        # TODO (week 3, part 3): tune the PID gains so that theta settles on theta_g within 10%
        # in 3 s or less, overshooting by 10% at most. With zero gains the robot never turns.
        self.Kp = 0
        self.Ki = 0
        self.Kd = 0
        # END CODE BLOCK

        # memory: accumulated error and previous error
        self.E_k = 0
        self.e_k_1 = 0

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w) that steer the robot to the goal."""
        x_g = inputs.x_g
        y_g = inputs.y_g
        x, y, theta = state_estimate.unpack()
        v = inputs.v

        # 1. Heading to the goal: u = (u_x, u_y) points from the robot to the goal.
        # START CODE BLOCK
        # TODO (week 3, part 1): u_x, u_y = the vector from the robot (x, y) to the goal
        # (x_g, y_g); theta_g = the angle it makes with the x axis (math.atan2).
        u_x = 0
        u_y = 0
        theta_g = 0
        # END CODE BLOCK

        # 2. Heading error, kept in [-pi, pi].
        # START CODE BLOCK
        # TODO (week 3, part 2): e_k = theta_g - theta, brought back into [-pi, pi]
        # (the atan2 of its sine and cosine does that).
        e_k = 0
        # END CODE BLOCK

        # 3. PID terms: proportional, integral (accumulated in self.E_k), derivative (from self.e_k_1).
        # START CODE BLOCK
        # TODO (week 3, part 3): e_P is this step's error; e_I adds e_k * dt to the error
        # accumulated so far (self.E_k); e_D is the change since the last step's error
        # (self.e_k_1) divided by dt. The code below stores e_I and e_k for the next step.
        e_P = 0
        e_I = 0
        e_D = 0
        # END CODE BLOCK

        w = self.Kp * e_P + self.Ki * e_I + self.Kd * e_D

        # save the errors for the next step
        self.E_k = e_I
        self.e_k_1 = e_k

        # what the plot shows as the reference heading
        self.theta_g = theta_g
        return v, w
