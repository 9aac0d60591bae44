"""AOandGTG: blend go-to-goal and avoid-obstacles into one heading (the manual, week 5, part 1).

u_gtg points from the robot to the goal; u_ao points away from what the IR sensors see (the weighted sum of
the vectors from the robot to the five IR points: this folder's AvoidObstacles computes it). Their blend
u_ao_gtg is a heading between the two, and a PID regulator steers along it: the robot heads for the goal
while it keeps clear of obstacles.

This is the course's sp14 release: u_gtg and u_ao are NOT normalised and alpha = 0.25. Then |u_gtg| is the
distance to the goal, so a far goal outweighs the obstacles (towards (-1, 1) in the week-5 world the
robot drives into the 60-degree bar). The manual suggests normalising both vectors first; that is a
valid answer too (the author's own week-5 answer normalised them, with alpha = 0.3).

Student block (week 5) and the placeholder the stub gets:
  execute: the blend u_ao_gtg of u_gtg and u_ao. Placeholder: `u_ao_gtg = np.zeros(2)` (heading 0: the
  robot turns towards the x axis, whatever it sees).
"""

import math

import numpy as np

from simiam.control import Controller

from .avoid_obstacles import AvoidObstacles


class AOandGTG(Controller):
    """Steers along u_ao_gtg, a blend of the go-to-goal vector u_gtg and the avoid-obstacles vector u_ao."""

    def __init__(self):
        super().__init__("ao_and_gtg")

        # gains of the PID regulator (the sp14 release's)
        self.Kp = 4
        self.Ki = 0.01
        self.Kd = 0.01

        # memory: accumulated error and previous error
        self.E_k = 0
        self.e_k_1 = 0

        # computes u_ao (and the IR points) exactly as the avoid_obstacles state does
        self.avoid = AvoidObstacles()

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w) that steer the robot along the blend of u_gtg and u_ao."""
        x, y, theta = state_estimate.unpack()

        # 1. u_ao: AvoidObstacles' weighted sum of the vectors from the robot to the IR points
        self.avoid.execute(robot, state_estimate, inputs, dt)
        u_ao = np.array(self.avoid.u_ao, dtype=float)

        # 2. u_gtg: from the robot to the goal
        u_gtg = np.array([inputs.x_g - x, inputs.y_g - y])

        # what the viewer draws (and the grader checks the blend against): the two vectors as given
        self.u_ao = u_ao.copy()
        self.u_gtg = u_gtg.copy()
        self.ir_distances_wf = self.avoid.ir_distances_wf

        # 3. Blend the two vectors into u_ao_gtg.
        # START CODE BLOCK
        alpha = 0.25
        u_ao_gtg = alpha * u_gtg + (1 - alpha) * u_ao
        # END CODE BLOCK

        # 4. The heading of the blend, and the error to it, kept in [-pi, pi]
        theta_ao_gtg = math.atan2(u_ao_gtg[1], u_ao_gtg[0])
        e_k = theta_ao_gtg - theta
        e_k = math.atan2(math.sin(e_k), math.cos(e_k))

        # PID regulator on the heading error
        e_P = e_k
        e_I = self.E_k + e_k * dt
        e_D = (e_k - self.e_k_1) / dt
        w = self.Kp * e_P + self.Ki * e_I + self.Kd * e_D

        # save the errors for the next step
        self.E_k = e_I
        self.e_k_1 = e_k

        # the heading reference and the blend, for the viewer
        self.theta_g = theta_ao_gtg
        self.u_ao_gtg = u_ao_gtg
        return inputs.v, w
