"""AOandGTG: blend go-to-goal and avoid-obstacles into one heading (week 5; shipped filled in from week 6).

u_gtg points from the robot to the goal, u_ao away from what the IR sensors see (as in AvoidObstacles);
the robot steers along u_ao_gtg = alpha * u_gtg + (1 - alpha) * u_ao with a PID regulator.

Student block (week 5) and the placeholder the stub gets:
  execute: u_ao_gtg.  Placeholder: `u_ao_gtg = np.zeros(2)` (heading 0).
"""

import math

import numpy as np

from simiam.control import Controller

from .avoid_obstacles import AvoidObstacles


class AOandGTG(Controller):
    """Steers along the blend of u_gtg (to inputs.x_g, inputs.y_g) and u_ao; v = inputs.v."""

    # The IR points in the world frame come from the week-4 geometry, as in AvoidObstacles.
    apply_sensor_geometry = AvoidObstacles.apply_sensor_geometry
    get_transformation_matrix = AvoidObstacles.get_transformation_matrix

    def __init__(self):
        super().__init__("ao_and_gtg")

        # gains of the PID regulator
        self.Kp = 4
        self.Ki = 0.01
        self.Kd = 0.01

        # memory: accumulated error and previous error
        self.E_k = 0
        self.e_k_1 = 0

        self.u_gtg = None
        self.u_ao_gtg = None

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w) that steer along the blend of u_gtg and u_ao."""
        x, y, theta = state_estimate.unpack()

        ir_distances = robot.get_ir_distances()
        ir_distances_rf, ir_distances_wf = self.apply_sensor_geometry(robot, ir_distances, state_estimate)

        # the avoid-obstacles vector, as in AvoidObstacles
        sensor_gains = [1, 1, 0.5, 1, 1]
        u_i = (np.asarray(ir_distances_wf)[0:2, :] - np.array([[x], [y]])) * sensor_gains
        u_ao = np.sum(u_i, axis=1)

        # the go-to-goal vector
        u_gtg = np.array([inputs.x_g - x, inputs.y_g - y])

        # Blend u_gtg and u_ao.
        # START CODE BLOCK
        alpha = 0.25
        u_ao_gtg = alpha * u_gtg + (1 - alpha) * u_ao
        # END CODE BLOCK

        theta_ao_gtg = math.atan2(u_ao_gtg[1], u_ao_gtg[0])
        e_k = theta_ao_gtg - theta
        e_k = math.atan2(math.sin(e_k), math.cos(e_k))

        e_P = e_k
        e_I = self.E_k + e_k * dt
        e_D = (e_k - self.e_k_1) / dt
        w = self.Kp * e_P + self.Ki * e_I + self.Kd * e_D

        self.E_k = e_I
        self.e_k_1 = e_k

        self.theta_g = theta_ao_gtg
        self.u_ao = u_ao
        self.u_gtg = u_gtg
        self.u_ao_gtg = u_ao_gtg
        self.ir_distances_wf = ir_distances_wf
        return inputs.v, w
