"""FollowWall: drive along a wall at the distance d_fw, with the wall on the left or on the right.

The IR points in the world frame come from AvoidObstacles' apply_sensor_geometry (week 4). Two IR points
on the wall estimate it as a line: p_1 and p_2, the points of the two sensors on the chosen side that
measure the shortest distances (sensors 1, 2, 3 for the left, 5, 4, 3 for the right; index 0..4 here).
Along the wall: u_fw_t = p_2 - p_1, and its unit vector u_fw_tp. Toward the wall: u_fw_p, the vector from
the robot (u_p) to the nearest point of that line (through u_a = p_1); its length is the distance to the
wall. u_fw_pp = u_fw_p - d_fw * u_fw_p/|u_fw_p| points toward the point d_fw from the wall (it is zero at
distance d_fw). The robot steers along u_fw = d_fw * u_fw_tp + u_fw_pp.

Student block (week 6) and the placeholders the stub gets:
  execute: p_1, p_2 (the two wall points), u_fw_t, u_fw_tp, u_a, u_p, u_fw_p, u_fw_pp, u_fw.
    Placeholder: p_1 = p_2 = the point of sensor 0 and every vector zero, so u_fw is zero and the robot
    turns to heading 0 (along the x axis), whatever it sees.

The sp14 code kept the unit vector u_fw_p/|u_fw_p| in a variable named u_fw_pp; here u_fw_pp is the
manual's vector toward the point d_fw from the wall (zero at d_fw).
"""

import math

import numpy as np

from simiam.control import Controller, norm

from .avoid_obstacles import AvoidObstacles


class FollowWall(Controller):
    """Steers along u_fw: the wall on the side inputs.direction ("left" or "right"), at inputs.d_fw."""

    def __init__(self):
        super().__init__("follow_wall")

        # gains of the PID regulator (the course's: a P regulator)
        self.Kp = 2
        self.Ki = 0
        self.Kd = 0

        # memory: accumulated error and previous error
        self.E_k = 0
        self.e_k_1 = 0

        # the IR points in the world frame, as the avoid_obstacles state computes them (week 4)
        self.geometry = AvoidObstacles()

        # what the viewer and the checks read after each call
        self.p_1 = None
        self.p_2 = None
        self.u_fw_t = None
        self.u_fw_tp = None
        self.u_fw_p = None
        self.u_fw_pp = None
        self.u_fw = None

    def execute(self, robot, state_estimate, inputs, dt):
        """Return (v, w) that keep the robot at inputs.d_fw from the wall on the side inputs.direction."""
        x, y, theta = state_estimate.unpack()

        # the five IR distances, and the points they measure (columns, homogeneous coordinates)
        ir_distances = robot.get_ir_distances()
        _, ir_distances_wf = self.geometry.apply_sensor_geometry(robot, ir_distances, state_estimate)
        ir_distances_wf = np.asarray(ir_distances_wf)

        direction = inputs.direction  # "left" or "right" ("" counts as left, as in the original)
        d_fw = inputs.d_fw

        # Estimate the wall from two IR points, then the vector to steer along.
        # START CODE BLOCK
        # The two sensors on the chosen side that see the wall closest. sorted() keeps the candidates'
        # order on ties, as the original's sort did: left prefers 0, 1, 2; right prefers 4, 3, 2.
        if direction == "right":
            candidates = [4, 3, 2]
        else:
            candidates = [0, 1, 2]
        closest = sorted(candidates, key=lambda i: ir_distances[i])[:2]
        # p_1 -> p_2 runs along the wall in the robot's direction of travel: for the left side from the
        # lower sensor index to the higher, for the right side from the higher to the lower.
        if direction == "right":
            i_1, i_2 = max(closest), min(closest)
        else:
            i_1, i_2 = min(closest), max(closest)
        p_1 = ir_distances_wf[0:2, i_1]
        p_2 = ir_distances_wf[0:2, i_2]

        # along the wall
        u_fw_t = p_2 - p_1
        u_fw_tp = u_fw_t / norm(u_fw_t)

        # from the robot to the nearest point of the wall's line
        u_a = p_1
        u_p = np.array([x, y])
        u_fw_p = (u_a - u_p) - ((u_a - u_p) @ u_fw_tp) * u_fw_tp

        # toward the point d_fw away from the wall (d_fw times the unit vector, in this order, rounds as
        # the original did: the recorded runs are matched step for step)
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

        # what the viewer draws and the checks read
        self.theta_g = theta_fw
        self.p_1, self.p_2 = p_1, p_2
        self.u_fw_t, self.u_fw_tp = u_fw_t, u_fw_tp
        self.u_fw_p, self.u_fw_pp, self.u_fw = u_fw_p, u_fw_pp, u_fw
        self.ir_distances_wf = ir_distances_wf
        return inputs.v, w
