"""GoToGoal: a PID regulator that steers the robot to the goal (x_g, y_g) at a constant speed v.

Student blocks (week 3) and the placeholders the stub gets:
  1. __init__ gains: `self.Kp = 0`, `self.Ki = 0`, `self.Kd = 0` (tune them: theta should settle within
     10% in 3 s or less, with at most 10% overshoot).
  2. heading to the goal: `u_x = 0`, `u_y = 0`, `theta_g = 0`.
  3. heading error wrapped into [-pi, pi]: `e_k = 0`.
  4. PID terms: `e_P = 0`, `e_I = 0`, `e_D = 0`.
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
        # PID gains (tuned)
        self.Kp=4.0
        self.Ki=0.02

        self.Kd=0.1
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
        delta_x = x_g-x   # x distance
        delta_y = y_g-y   # y distance
        u_x, u_y = delta_x, delta_y
        theta_g = math.atan2( delta_y, delta_x )
        # END CODE BLOCK

        # 2. Heading error, kept in [-pi, pi].
        # START CODE BLOCK
        two_pi = 2*math.pi
        # wrap the error
        err = theta_g - theta
        while err  >  math.pi:
            err -= two_pi
        while err  <  -math.pi:
            err += two_pi
        e_k = err
        # END CODE BLOCK

        # 3. PID terms: proportional, integral (accumulated in self.E_k), derivative (from self.e_k_1).
        # START CODE BLOCK
        last = self.e_k_1
        acc = self.E_k + dt*e_k    # integral
        e_P = e_k
        e_I = acc
        e_D = (e_k - last)/dt  # derivative
        # END CODE BLOCK

        w = self.Kp * e_P + self.Ki * e_I + self.Kd * e_D

        # save the errors for the next step
        self.E_k = e_I
        self.e_k_1 = e_k

        # what the plot shows as the reference heading
        self.theta_g = theta_g
        return v, w
