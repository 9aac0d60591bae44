"""FollowWall: drive along a wall at the distance d_fw, the wall on the left or on the right (week 6).

Two IR points on the wall give a piece of it: u_fw_t runs along the wall (from p_1 to p_2), u_fw_p from
the robot to the nearest point of the wall's line. Steering along u_fw = d_fw * u_fw_tp + u_fw_pp keeps
the robot moving along the wall (u_fw_tp) and pulls it to the distance d_fw (u_fw_pp is zero there).

inputs.direction says which side the wall is on: "left" uses sensors 1-3, "right" sensors 5-3 ("" is
treated as "left", as the original did); inputs.d_fw is the distance to keep (m).

Student block (week 6, shipped filled in from week 7) and the placeholder the stub would get:
  p_1, p_2 = the point of sensor 1 (left) or 5 (right) twice, and every vector [0, 0] (the robot turns
  to the heading 0).
"""

import math

import numpy as np

from simiam.control import Controller, norm


class FollowWall(Controller):
    """Steers along u_fw to follow the wall on inputs.direction at inputs.d_fw; v = inputs.v."""

    def __init__(self):
        super().__init__("follow_wall")

        # gains of the PID regulator
        self.Kp = 2
        self.Ki = 0
        self.Kd = 0

        # memory: accumulated error and previous error
        self.E_k = 0
        self.e_k_1 = 0

        # the vectors of the last step, for the viewer
        self.u_fw_t = None
        self.u_fw_p = None
        self.u_fw = None

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w) that steer the robot along the wall."""
        x, y, theta = state_estimate.unpack()

        # the five IR distances, and the points they measure in the world frame
        ir_distances = robot.get_ir_distances()
        ir_distances_wf = self.apply_sensor_geometry(robot, ir_distances, state_estimate)

        d_fw = inputs.d_fw

        # START CODE BLOCK
        # 1. The two sensors of the wall's side that read the shortest distances (ties: the order below,
        #    as MATLAB's stable sort); p_1 is the rear one, p_2 the front one, so u_fw_t runs forward.
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

        # 2. u_fw_p: from the robot (u_p) to the nearest point of the wall's line through u_a = p_1.
        u_fw_tp = u_fw_t / norm(u_fw_t)
        u_a = p_1
        u_p = np.array([x, y])
        u_fw_p = (u_a - u_p) - ((u_a - u_p) @ u_fw_tp) * u_fw_tp

        # 3. u_fw_pp is zero at the distance d_fw from the wall; u_fw combines it with u_fw_tp.
        u_fw_pp = u_fw_p - d_fw * (u_fw_p / norm(u_fw_p))
        u_fw = d_fw * u_fw_tp + u_fw_pp
        # END CODE BLOCK

        # heading along u_fw, and its error kept in [-pi, pi]
        theta_fw = math.atan2(u_fw[1], u_fw[0])
        e_k = theta_fw - theta
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
        self.theta_g = theta_fw
        self.u_fw_t = u_fw_t
        self.u_fw_p = u_fw_p
        self.u_fw = u_fw
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
