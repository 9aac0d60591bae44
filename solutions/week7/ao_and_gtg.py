"""AOandGTG: blend go-to-goal and avoid-obstacles into one heading (week 5).

u_gtg points from the robot to the goal, u_ao away from what the IR sensors see (as in AvoidObstacles);
the blend u_ao_gtg = alpha * u_gtg + (1 - alpha) * u_ao steers the robot toward the goal while it keeps
clear of an obstacle it is next to. Neither vector is normalised, as in the original's final release
(alpha = 0.25): far from the goal, u_gtg dominates.

Student block (week 5, shipped filled in from week 6) and the placeholder the stub would get:
  the blend: `alpha = 0`, `u_ao_gtg = u_gtg` (the robot only goes to the goal).
"""

import math

import numpy as np

from simiam.control import Controller


class AOandGTG(Controller):
    """Steers along u_ao_gtg, the blend of u_gtg (to the goal) and u_ao (from obstacles); v = inputs.v."""

    def __init__(self):
        super().__init__("ao_and_gtg")

        # gains of the PID regulator
        self.Kp = 4
        self.Ki = 0.01
        self.Kd = 0.01

        # memory: accumulated error and previous error
        self.E_k = 0
        self.e_k_1 = 0

        # the vectors of the last step, for the viewer
        self.u_gtg = None
        self.u_ao_gtg = None

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w) that steer the robot along the blend of u_gtg and u_ao."""
        x, y, theta = state_estimate.unpack()

        # the five IR distances, and the points they measure in the world frame
        ir_distances = robot.get_ir_distances()
        ir_distances_wf = self.apply_sensor_geometry(robot, ir_distances, state_estimate)

        # u_gtg: from the robot to the goal
        u_gtg = np.array([inputs.x_g - x, inputs.y_g - y])

        # u_ao: the weighted vectors from the robot to the IR points, summed (as AvoidObstacles)
        sensor_gains = [1, 1, 0.5, 1, 1]
        u_i = (ir_distances_wf[0:2, :] - np.array([[x], [y]])) * sensor_gains
        u_ao = np.sum(u_i, axis=1)

        # Blend the two vectors into u_ao_gtg.
        # START CODE BLOCK
        alpha = 0.25
        u_ao_gtg = alpha * u_gtg + (1 - alpha) * u_ao
        # END CODE BLOCK

        # heading of the blend, and its error kept in [-pi, pi]
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

        # what the viewer draws
        self.theta_g = theta_ao_gtg
        self.u_gtg = u_gtg
        self.u_ao = u_ao
        self.u_ao_gtg = u_ao_gtg
        self.ir_distances_wf = ir_distances_wf
        return inputs.v, w

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
