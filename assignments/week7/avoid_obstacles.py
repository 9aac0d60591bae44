"""AvoidObstacles: steer away from what the IR sensors see, toward free space.

Each IR distance d_i is a point (d_i, 0) in its sensor's frame; the sensor's mount pose moves it into
the robot frame, the estimated robot pose into the world frame (the manual, section 4.4). The weighted
vectors from the robot to these points add up to u_ao, and a PID regulator steers along it.

Student blocks (week 4, shipped filled in from week 5) and the placeholders the week-4 stub gets:
  1. __init__ gains (tunable, as the manual allows). Placeholder: the course's `self.Kp = 4`,
     `self.Ki = 0.01`, `self.Kd = 0.1`.
  2. execute: sensor_gains, u_i, u_ao, theta_ao, e_k. Placeholder: `sensor_gains = [0, 0, 0, 0, 0]`,
     `u_i = np.zeros((2, 5))`, `u_ao = np.sum(u_i, axis=1)`, `theta_ao = 0`, `e_k = 0`
     (the robot drives straight).
  3. apply_sensor_geometry: sensor frame -> robot frame -> world frame. Placeholder:
     `ir_distances_rf = np.zeros((3, 5))` and `ir_distances_wf = np.zeros((3, 5))`.
  4. get_transformation_matrix: Placeholder `T = np.zeros((3, 3))`.
"""

import math

import numpy as np

from simiam.control import Controller


class AvoidObstacles(Controller):
    """Steers along u_ao, the weighted sum of the vectors from the robot to the IR points; v = inputs.v."""

    def __init__(self):
        super().__init__("avoid_obstacles")

        # gains of the PID regulator
        # START CODE BLOCK
        # The gains the course shipped from week 5 on (the sp14 release), with which the recorded
        # week-5 runs were made.
        self.Kp = 4
        self.Ki = 0.01
        self.Kd = 0.01
        # END CODE BLOCK

        # memory: accumulated error and previous error
        self.E_k = 0
        self.e_k_1 = 0

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w) that steer the robot away from obstacles."""
        x, y, theta = state_estimate.unpack()

        # the five IR distances, and the points they measure (columns, homogeneous coordinates)
        ir_distances = robot.get_ir_distances()
        ir_distances_rf, ir_distances_wf = self.apply_sensor_geometry(robot, ir_distances, state_estimate)

        # Weigh the vector from the robot to each point, sum them into u_ao, steer along u_ao.
        # START CODE BLOCK
        sensor_gains = [1, 1, 0.5, 1, 1]  # symmetric: sensors 1/5 and 2/4 weigh the same
        u_i = (np.asarray(ir_distances_wf)[0:2, :] - np.array([[x], [y]])) * sensor_gains
        u_ao = np.sum(u_i, axis=1)

        theta_ao = math.atan2(u_ao[1], u_ao[0])
        e_k = theta_ao - theta
        e_k = math.atan2(math.sin(e_k), math.cos(e_k))
        # END CODE BLOCK

        # PID regulator on the heading error
        e_P = e_k
        e_I = self.E_k + e_k * dt
        e_D = (e_k - self.e_k_1) / dt
        w = self.Kp * e_P + self.Ki * e_I + self.Kd * e_D

        # save the errors for the next step
        self.E_k = e_I
        self.e_k_1 = e_k

        # what the viewer draws: the heading reference, u_ao and the IR points
        self.theta_g = theta_ao
        self.u_ao = u_ao
        self.ir_distances_wf = ir_distances_wf
        return inputs.v, w

    def apply_sensor_geometry(self, robot, ir_distances, state_estimate):
        """The IR points in the robot frame and in the world frame: two 3x5 arrays, one column a sensor."""
        n_sensors = len(ir_distances)

        # START CODE BLOCK
        # sensor frame -> robot frame, with each sensor's mount pose (x_s, y_s, theta_s)
        ir_distances_rf = np.zeros((3, n_sensors))
        for i in range(n_sensors):
            x_s, y_s, theta_s = robot.ir_array[i].location.unpack()
            T = np.asarray(self.get_transformation_matrix(x_s, y_s, theta_s))
            ir_distances_rf[:, i] = T @ np.array([ir_distances[i], 0.0, 1.0])

        # robot frame -> world frame, with the estimated pose of the robot
        x, y, theta = state_estimate.unpack()
        T = np.asarray(self.get_transformation_matrix(x, y, theta))
        ir_distances_wf = T @ ir_distances_rf
        # END CODE BLOCK

        return ir_distances_rf, ir_distances_wf

    def get_transformation_matrix(self, x, y, theta):
        """T(x, y, theta): rotate by theta, then translate by (x, y) (3x3, homogeneous coordinates)."""
        # START CODE BLOCK
        T = np.array([
            [math.cos(theta), -math.sin(theta), x],
            [math.sin(theta), math.cos(theta), y],
            [0.0, 0.0, 1.0],
        ])
        # END CODE BLOCK
        return T
