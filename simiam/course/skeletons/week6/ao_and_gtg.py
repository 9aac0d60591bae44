"""AOandGTG: blend go-to-goal and avoid-obstacles into one heading (the manual, week 5, part 1).

u_gtg points from the robot to the goal; u_ao points away from what the IR sensors see (the weighted sum of
the vectors from the robot to the five IR points, as AvoidObstacles computes it). Their blend u_ao_gtg is
a heading between the two, and a PID regulator steers along it: the robot heads for the goal while it
keeps clear of obstacles.

This is the course's sp14 release: u_gtg and u_ao are NOT normalised and alpha = 0.25. Then |u_gtg| is the
distance to the goal, so a far goal outweighs the obstacles (towards (-1, 1) in the week-5 world the
robot drives into the 60-degree bar). The manual suggests normalising both vectors first; that is a
valid answer too.

Student block (week 5) and the placeholder the stub gets:
  execute: the blend u_ao_gtg of u_gtg and u_ao. Placeholder: `u_ao_gtg = np.zeros(2)` (heading 0: the
  robot turns towards the x axis, whatever it sees).
"""

import math

import numpy as np

from simiam.control import Controller


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

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w) that steer the robot along the blend of u_gtg and u_ao."""
        x, y, theta = state_estimate.unpack()

        # 1. u_ao: the weighted vectors from the robot to the IR points in the world frame, summed
        ir_distances = robot.get_ir_distances()
        ir_distances_wf = self.apply_sensor_geometry(robot, ir_distances, state_estimate)
        sensor_gains = [1, 1, 0.5, 1, 1]
        u_i = (ir_distances_wf[0:2, :] - np.array([[x], [y]])) * sensor_gains
        u_ao = np.sum(u_i, axis=1)

        # 2. u_gtg: from the robot to the goal
        u_gtg = np.array([inputs.x_g - x, inputs.y_g - y])

        # 3. Blend the two vectors into u_ao_gtg.
        # START CODE BLOCK
        # TODO (week 5, part 1): u_ao_gtg = a blend of u_gtg (from the robot to the goal) and u_ao
        # (away from the obstacles), both 2-vectors (numpy arrays): alpha * u_gtg + (1 - alpha) * u_ao
        # with 0 < alpha < 1 lies between them. You may normalise both first (np.linalg.norm; mind a
        # zero vector). Until then the heading is 0: the robot turns to face the x axis.
        u_ao_gtg = np.zeros(2)
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

        # what the viewer draws: the heading reference, the three vectors and the IR points
        self.theta_g = theta_ao_gtg
        self.u_gtg = u_gtg
        self.u_ao = u_ao
        self.u_ao_gtg = u_ao_gtg
        self.ir_distances_wf = ir_distances_wf
        return inputs.v, w

    def apply_sensor_geometry(self, robot, ir_distances, state_estimate):
        """The IR points in the world frame: a 3x5 array, one column (x, y, 1) a sensor."""
        # sensor frame -> robot frame, with each sensor's mount pose (x_s, y_s, theta_s)
        ir_distances_rf = np.zeros((3, 5))
        for i in range(5):
            x_s, y_s, theta_s = robot.ir_array[i].location.unpack()
            T = self.get_transformation_matrix(x_s, y_s, theta_s)
            ir_distances_rf[:, i] = T @ np.array([ir_distances[i], 0.0, 1.0])

        # robot frame -> world frame, with the estimated pose of the robot
        x, y, theta = state_estimate.unpack()
        return self.get_transformation_matrix(x, y, theta) @ ir_distances_rf

    def get_transformation_matrix(self, x, y, theta):
        """T(x, y, theta): rotate by theta, then translate by (x, y) (3x3, homogeneous coordinates)."""
        return np.array([
            [math.cos(theta), -math.sin(theta), x],
            [math.sin(theta), math.cos(theta), y],
            [0.0, 0.0, 1.0],
        ])
