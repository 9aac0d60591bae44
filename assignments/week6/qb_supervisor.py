"""QBSupervisor for week 6: follow a wall with FollowWall, on the left or on the right, at the distance d_fw.

Test settings: `fw_direction` ("left" or "right") and `d_fw` (the distance to keep from the wall) are set in
the constructor's block; v in __init__. There is no switching this week: the robot always follows a wall.
ensure_w is provided: the course's dead-zone version, shipped filled in since week 4 (not week 3's).

Student blocks and the placeholders the stub gets:
  __init__ (week 6): d_fw, fw_direction. Placeholder: `self.d_fw = 0` and `self.fw_direction = "left"`
    (the robot drives into the wall; the original release's d_fw = 0.1 clips the obstacle within 3 s).
  update_odometry (week 2, shipped filled in): `x_dt = 0`, `y_dt = 0`, `theta_dt = 0`.
"""

import math

from simiam.control import Stop, Supervisor

from .ao_and_gtg import AOandGTG
from .avoid_obstacles import AvoidObstacles
from .follow_wall import FollowWall
from .go_to_angle import GoToAngle
from .go_to_goal import GoToGoal


def sign(x):
    """MATLAB's sign: -1, 0 or 1, for any real number (int, float, bool or a numpy scalar)."""
    # not (x > 0) - (x < 0): numpy refuses to subtract the numpy bools a numpy float's comparisons give
    if x > 0:
        return 1
    if x < 0:
        return -1
    return 0


class QBSupervisor(Supervisor):
    """Runs FollowWall with the wall on the side fw_direction, at the distance d_fw."""

    def __init__(self):
        super().__init__()
        self.add_controller(Stop())
        self.add_controller(GoToAngle())
        self.add_controller(GoToGoal())
        self.add_controller(AvoidObstacles())
        self.add_controller(AOandGTG())
        self.add_controller(FollowWall())
        self.switch_to_state("follow_wall")

        self.theta_d = math.pi / 4
        self.v = 0.15  # m/s
        self.goal = (-1.0, 1.0)
        self.d_stop = 0.05  # m

        # the wall to follow: its side ("left" or "right") and the distance to keep from it (m)
        # START CODE BLOCK
        # TODO (week 6): d_fw = the distance (m) to keep from the wall, which the IR sensors must
        # see (they read 0.04 to 0.3 m); fw_direction = the side of the wall, "left" or "right".
        # Until then d_fw is 0 and the robot drives into the wall.
        self.d_fw = 0
        self.fw_direction = "left"
        # END CODE BLOCK

    def execute(self, dt):
        """One step: odometry, then FollowWall (direction = fw_direction, d_fw), ensure_w, wheel speeds."""
        self.update_odometry()

        inputs = self.inputs()  # v, the goal, direction = self.fw_direction, d_fw = self.d_fw

        v, w = self.execute_controller(inputs, dt)

        vel_r, vel_l = self.ensure_w(self.robot, v, w)
        self.robot.set_wheel_speeds(vel_r, vel_l)

    def ensure_w(self, robot, v, w):
        """Wheel speeds that keep w as well as possible, with both wheels inside [min_vel, max_vel].

        The motors stall below min_vel: a moving robot keeps both wheels at least at min_vel, turning in
        the direction of v; a robot with v = 0 turns on the spot at least at its slowest possible w.
        """
        R = robot.wheel_radius
        L = robot.wheel_base_length
        vel_max = robot.max_vel
        vel_min = robot.min_vel

        if abs(v) > 0:
            # 1. Limit v, w to what the motors can do (no stalling, no exceeding max_vel)
            v_lim = max(min(abs(v), (R / 2) * (2 * vel_max)), (R / 2) * (2 * vel_min))
            w_lim = max(min(abs(w), (R / L) * (vel_max - vel_min)), 0)

            # 2. Wheel speeds for the limited (v, w)
            vel_r_d, vel_l_d = robot.dynamics.uni_to_diff(robot, v_lim, w_lim)

            # 3. The faster and the slower wheel
            vel_rl_max = max(vel_r_d, vel_l_d)
            vel_rl_min = min(vel_r_d, vel_l_d)

            # 4. Shift both wheels into [vel_min, vel_max]
            if vel_rl_max > vel_max:
                vel_r = vel_r_d - (vel_rl_max - vel_max)
                vel_l = vel_l_d - (vel_rl_max - vel_max)
            elif vel_rl_min < vel_min:
                vel_r = vel_r_d + (vel_min - vel_rl_min)
                vel_l = vel_l_d + (vel_min - vel_rl_min)
            else:
                vel_r = vel_r_d
                vel_l = vel_l_d

            # 5. Back to (v, w), with the signs of the request
            v_shift, w_shift = robot.dynamics.diff_to_uni(robot, vel_r, vel_l)
            v = sign(v) * v_shift
            w = sign(w) * w_shift
        else:
            # Standing still: either no turn, or a turn between the slowest and the fastest possible w
            w_min = R / L * (2 * vel_min)
            w_max = R / L * (2 * vel_max)
            if abs(w) > w_min:
                w = sign(w) * max(min(abs(w), w_max), w_min)
            else:
                w = 0

        vel_r, vel_l = robot.dynamics.uni_to_diff(robot, v, w)
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
