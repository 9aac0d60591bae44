"""SlidingMode (provided): the three vectors the sliding test of week 7 compares.

The supervisor's events sliding_left and sliding_right run it for one direction, then solve
[u_gtg u_ao] sigma = u_fw. It never drives the robot (its (v, w) is (0, 0)) and keeps no memory.

  u_gtg: from the robot to the goal;
  u_ao:  the weighted sum of the vectors from the robot to the IR points (as AvoidObstacles);
  u_fw:  the direction of the wall as FollowWall picks it (the two nearest sensors on that side),
         stored as in the original course: the POINT (x + cos(theta_fw), y + sin(theta_fw)), one metre
         from the robot along the wall, not the unit vector (cos(theta_fw), sin(theta_fw)). The sliding
         test therefore decomposes that point; the course's reference solution and its recorded runs do
         the same, so it is kept.

Nothing to write here.
"""

import math

import numpy as np

from simiam.control import Controller


class SlidingMode(Controller):
    """Computes u_gtg, u_ao and u_fw for inputs.direction ("left" or "right"); returns (0, 0)."""

    def __init__(self):
        super().__init__("sliding_mode")
        self.u_gtg = None
        self.u_ao = None
        self.u_fw = None

    def execute(self, robot, state_estimate, inputs, dt):
        """Store u_gtg, u_ao and u_fw for the current estimate and IR readings; return (0, 0)."""
        x, y, theta = state_estimate.unpack()

        ir_distances = robot.get_ir_distances()
        ir_distances_wf = self.apply_sensor_geometry(robot, ir_distances, state_estimate)

        # 1. u_gtg
        self.u_gtg = np.array([inputs.x_g - x, inputs.y_g - y])

        # 2. u_ao
        sensor_gains = [1, 1, 0.5, 1, 1]
        u_i = (ir_distances_wf[0:2, :] - np.array([[x], [y]])) * sensor_gains
        self.u_ao = np.sum(u_i, axis=1)

        # 3. u_fw: FollowWall's choice of p_1 and p_2 (ties keep the order below, as MATLAB's stable sort)
        if inputs.direction == "right":
            candidates = [4, 3, 2]  # sensors 5, 4, 3
        else:
            candidates = [0, 1, 2]  # sensors 1, 2, 3
        s_1, s_2 = sorted(candidates, key=lambda i: ir_distances[i])[0:2]
        if inputs.direction == "right":
            p_1 = ir_distances_wf[0:2, max(s_1, s_2)]
            p_2 = ir_distances_wf[0:2, min(s_1, s_2)]
        else:
            p_1 = ir_distances_wf[0:2, min(s_1, s_2)]
            p_2 = ir_distances_wf[0:2, max(s_1, s_2)]
        u_fw_t = p_2 - p_1
        theta_fw = math.atan2(u_fw_t[1], u_fw_t[0])
        self.u_fw = np.array([x + math.cos(theta_fw), y + math.sin(theta_fw)])

        self.theta_g = theta_fw
        self.ir_distances_wf = ir_distances_wf
        return 0, 0

    def apply_sensor_geometry(self, robot, ir_distances, state_estimate):
        """The IR points in the world frame: a 3x5 array, one column (x, y, 1) a sensor."""
        ir_distances_rf = np.zeros((3, 5))
        for i in range(5):
            x_s, y_s, theta_s = robot.ir_array[i].location.unpack()
            T = self.get_transformation_matrix(x_s, y_s, theta_s)
            ir_distances_rf[:, i] = T @ np.array([ir_distances[i], 0.0, 1.0])

        x, y, theta = state_estimate.unpack()
        return self.get_transformation_matrix(x, y, theta) @ ir_distances_rf

    def get_transformation_matrix(self, x, y, theta):
        """T(x, y, theta): rotate by theta, then translate by (x, y) (3x3, homogeneous coordinates)."""
        return np.array([
            [math.cos(theta), -math.sin(theta), x],
            [math.sin(theta), math.cos(theta), y],
            [0.0, 0.0, 1.0],
        ])
