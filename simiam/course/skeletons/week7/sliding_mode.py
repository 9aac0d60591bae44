"""SlidingMode (provided): the three vectors the sliding test of week 7 compares.

The supervisor's events sliding_left and sliding_right run it for one direction, then solve
[u_gtg u_ao] sigma = u_fw. It never drives the robot (its (v, w) is (0, 0)) and keeps no memory.

  u_gtg: from the robot to the goal;
  u_ao:  away from what the IR sensors see, as this folder's AvoidObstacles computes it;
  u_fw:  the direction of the wall this folder's FollowWall finds on that side (u_fw_t, from p_1 to p_2),
         stored as in the original course: the POINT (x + cos(theta_fw), y + sin(theta_fw)), one metre
         from the robot along the wall, not the unit vector (cos(theta_fw), sin(theta_fw)). The sliding
         test therefore decomposes that point; the course's reference solution and its recorded runs do
         the same, so it is kept.

Nothing to write here.
"""

import math

import numpy as np

from simiam.control import Controller

from .avoid_obstacles import AvoidObstacles
from .follow_wall import FollowWall


class SlidingMode(Controller):
    """Computes u_gtg, u_ao and u_fw for inputs.direction ("left" or "right"); returns (0, 0)."""

    def __init__(self):
        super().__init__("sliding_mode")
        # controllers of its own: SlidingMode reads their vectors and never lets them steer
        self.avoid = AvoidObstacles()
        self.follow = FollowWall()
        self.u_gtg = None
        self.u_ao = None
        self.u_fw = None

    def execute(self, robot, state_estimate, inputs, dt):
        """Store u_gtg, u_ao and u_fw for the current estimate and IR readings; return (0, 0)."""
        x, y, theta = state_estimate.unpack()

        # 1. u_gtg
        self.u_gtg = np.array([inputs.x_g - x, inputs.y_g - y])

        # 2. u_ao (a time step of 1 s: only the controller's PID uses it, and its w is not used)
        self.avoid.execute(robot, state_estimate, inputs, 1.0)
        self.u_ao = np.array(self.avoid.u_ao, dtype=float)

        # 3. u_fw: the wall's direction as FollowWall finds it on the side inputs.direction, as a point
        self.follow.execute(robot, state_estimate, inputs, 1.0)
        u_fw_t = self.follow.u_fw_t
        theta_fw = math.atan2(u_fw_t[1], u_fw_t[0])
        self.u_fw = np.array([x + math.cos(theta_fw), y + math.sin(theta_fw)])

        self.theta_g = theta_fw
        return 0, 0
