"""QBSupervisor for week 3: drive to the goal with GoToGoal and stop within d_stop of it.

Test settings (the manual's "How to test it all"): edit goal, v and d_stop in __init__.

Student blocks and the placeholders the stub gets:
  1. update_odometry (week 2, shipped filled in): `x_dt = 0`, `y_dt = 0`, `theta_dt = 0`.
  2. ensure_w (week 3): the shift of the wheel speeds. Placeholder: `vel_r = vel_r_d` and
     `vel_l = vel_l_d` (no shift: w is not ensured when a wheel saturates).
"""

import math

from simiam.control import Stop, Supervisor

from .go_to_angle import GoToAngle
from .go_to_goal import GoToGoal


class QBSupervisor(Supervisor):
    """Runs GoToGoal until the estimate is within d_stop of the goal, then Stop."""

    def __init__(self):
        super().__init__()
        self.add_controller(Stop())
        self.add_controller(GoToAngle())
        self.add_controller(GoToGoal())
        self.switch_to_state("go_to_goal")

        self.theta_d = math.pi / 4
        self.v = 0.2  # m/s
        self.goal = (-1.0, 1.0)
        self.d_stop = 0.05  # m

    def execute(self, dt):
        """One step: at_goal check, the controller, ensure_w, wheel speeds, then odometry (week-3 order)."""
        inputs = self.inputs()

        if self.check_event("at_goal"):
            self.switch_to_state("stop")

        v, w = self.execute_controller(inputs, dt)

        vel_r, vel_l = self.ensure_w(self.robot, v, w)
        self.robot.set_wheel_speeds(vel_r, vel_l)

        self.update_odometry()

    def ensure_w(self, robot, v, w):
        """Wheel speeds that keep the angular velocity w, giving up linear velocity v if a motor saturates."""
        # 1. Limit v and w to what the motors can do at all
        w = max(min(w, self.w_max_v0), -self.w_max_v0)
        v = max(min(v, self.v_max_w0), -self.v_max_w0)

        # 2. Wheel speeds needed for (v, w)
        vel_r_d, vel_l_d = robot.dynamics.uni_to_diff(robot, v, w)

        # 3. The faster and the slower wheel
        vel_rl_max = max(vel_r_d, vel_l_d)
        vel_rl_min = min(vel_r_d, vel_l_d)

        # 4. Shift both wheels by the same amount if one exceeds max_vel (this keeps w, lowers v)
        # START CODE BLOCK
        excess = 0
        limit = robot.max_vel
        if vel_rl_max > limit:
            excess = vel_rl_max - limit
        elif vel_rl_min < -limit:
            excess = vel_rl_min + limit
        vel_r = vel_r_d - excess
        vel_l = vel_l_d - excess
        # END CODE BLOCK

        return vel_r, vel_l

    def update_odometry(self):
        """Update self.state_estimate from how far each wheel turned since the last call."""
        robot = self.robot

        # wheel encoder ticks now, and at the last estimate
        right_ticks = robot.encoders[0].ticks
        left_ticks = robot.encoders[1].ticks
        prev_right_ticks = self.prev_ticks.right
        prev_left_ticks = self.prev_ticks.left

        # previous estimate
        x, y, theta = self.state_estimate.unpack()

        R = robot.wheel_radius
        L = robot.wheel_base_length
        m_per_tick = (2 * math.pi * R) / robot.encoders[0].ticks_per_rev

        # START CODE BLOCK
        d_right = (right_ticks - prev_right_ticks) * m_per_tick
        d_left = (left_ticks - prev_left_ticks) * m_per_tick
        d_center = (d_right + d_left) / 2
        phi = (d_right - d_left) / L

        x_dt = d_center * math.cos(theta)
        y_dt = d_center * math.sin(theta)
        theta_dt = phi
        # END CODE BLOCK

        theta_new = theta + theta_dt
        x_new = x + x_dt
        y_new = y + y_dt

        # remember the ticks for the next estimate
        self.prev_ticks.right = right_ticks
        self.prev_ticks.left = left_ticks

        # keep the estimated heading in [-pi, pi]
        self.state_estimate.set_pose((x_new, y_new, math.atan2(math.sin(theta_new), math.cos(theta_new))))
