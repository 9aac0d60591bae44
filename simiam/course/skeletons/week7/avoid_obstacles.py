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
        # Week 4: the PID gains that steer along u_ao. These values work; tune them if you like.
        self.Kp = 4
        self.Ki = 0.01
        self.Kd = 0.1
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
        # TODO (week 4, part 3): sensor_gains = one weight per sensor, the same on the left and
        # the right; u_i = column i is sensor_gains[i] times the vector from the robot (x, y) to
        # the IR point ir_distances_wf[:, i]; u_ao = the sum of the columns; theta_ao = its angle;
        # e_k = theta_ao - theta, kept in [-pi, pi]. Until then the robot drives straight.
        sensor_gains = [0, 0, 0, 0, 0]
        u_i = np.zeros((2, 5))
        u_ao = np.sum(u_i, axis=1)
        theta_ao = 0
        e_k = 0
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
        # TODO (week 4, parts 1 and 2): sensor i measured the point (ir_distances[i], 0) in its
        # own frame. Move it into the robot's frame with the sensor's mount pose
        # (robot.ir_array[i].location: x_s, y_s, theta_s), then into the world with the estimate
        # (x, y, theta), both with get_transformation_matrix. Column i of ir_distances_rf and of
        # ir_distances_wf holds that point as (x, y, 1).
        ir_distances_rf = np.zeros((3, 5))
        ir_distances_wf = np.zeros((3, 5))
        # END CODE BLOCK

        return ir_distances_rf, ir_distances_wf

    def get_transformation_matrix(self, x, y, theta):
        """T(x, y, theta): rotate by theta, then translate by (x, y) (3x3, homogeneous coordinates)."""
        # START CODE BLOCK
        # TODO (week 4, part 1): T = the 3x3 matrix that rotates a point (x, y, 1) by theta,
        # then translates it by (x, y).
        T = np.zeros((3, 3))
        # END CODE BLOCK
        return T
