"""QBSupervisor for week 2: steer to the angle theta_d and estimate the pose by odometry.

Test settings (the manual's "How to test it all"): edit theta_d and v in __init__.

Student block (week 2) and the placeholder the stub gets:
  update_odometry: x_dt, y_dt, theta_dt from the tick differences, m_per_tick, R, L and theta.
    Placeholder: `x_dt = 0`, `y_dt = 0`, `theta_dt = 0` (the estimate stays at the start pose).
"""

import math

from simiam.control import Stop, Supervisor

from .go_to_angle import GoToAngle


class QBSupervisor(Supervisor):
    """Runs GoToAngle and keeps the odometry estimate in self.state_estimate."""

    def __init__(self):
        super().__init__()
        self.add_controller(Stop())
        self.add_controller(GoToAngle())
        self.switch_to_state("go_to_angle")

        self.theta_d = math.pi / 4
        self.v = 0.1  # m/s
        self.goal = (-1.0, 1.0)
        self.d_stop = 0.05

    def execute(self, dt):
        """One step: the controller, the wheel speeds, then odometry (the original's week-2 order)."""
        inputs = self.inputs()
        v, w = self.execute_controller(inputs, dt)

        vel_r, vel_l = self.robot.dynamics.uni_to_diff(self.robot, v, w)
        self.robot.set_wheel_speeds(vel_r, vel_l)

        self.update_odometry()

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
        # TODO (week 2): estimate how the pose changed since the last call.
        # A wheel covered (its ticks now - its ticks then) * m_per_tick metres. From the right and
        # left distances, L and theta, compute x_dt, y_dt and theta_dt. Until then the estimate
        # never leaves the start pose.
        x_dt = 0
        y_dt = 0
        theta_dt = 0
        # END CODE BLOCK

        theta_new = theta + theta_dt
        x_new = x + x_dt
        y_new = y + y_dt

        # remember the ticks for the next estimate
        self.prev_ticks.right = right_ticks
        self.prev_ticks.left = left_ticks

        self.state_estimate.set_pose((x_new, y_new, theta_new))
