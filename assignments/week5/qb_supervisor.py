"""QBSupervisor for week 5: drive to the goal around obstacles, blending or switching between controllers.

Two ways to get there (the manual, week 5):
  * blending (`is_blending = True`, the default): AOandGTG steers along a blend of u_gtg and u_ao until
    the robot is at the goal, then Stop;
  * switching (`is_blending = False`): your block below picks the state each step from the events
    at_goal, unsafe, at_obstacle (and obstacle_cleared): Stop, AvoidObstacles, AOandGTG or GoToGoal.
Events look at all five IR sensors, the sides too: "at_obstacle" is any distance under d_at_obs (0.25 m),
"unsafe" any under d_unsafe (0.10 m), "obstacle_cleared" all over d_at_obs; "at_goal" compares the
*estimate* with the goal (d_stop 0.05 m). A switch resets the new controller and counts in
`self.switch_count`.

Test settings: edit v, goal and is_blending in __init__.

Student block and the placeholder the stub gets:
  execute (week 5): the switching. Placeholder: `self.switch_to_state("stop")` (the robot stays put).
Shipped filled in: update_odometry (week 2). ensure_w is provided.
"""

import math

from simiam.control import Stop, Supervisor

from .ao_and_gtg import AOandGTG
from .avoid_obstacles import AvoidObstacles
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
    """Blends (AOandGTG) or switches between GoToGoal, AvoidObstacles and AOandGTG until at the goal."""

    def __init__(self):
        super().__init__()
        self.add_controller(Stop())
        self.add_controller(GoToAngle())
        self.add_controller(GoToGoal())
        self.add_controller(AvoidObstacles())
        self.add_controller(AOandGTG())
        self.switch_to_state("ao_and_gtg")

        self.theta_d = math.pi / 4
        self.v = 0.15  # m/s
        # the manual's goal; the release's (-1, 1) makes the sp14 blend drive into the 60-degree bar
        self.goal = (1.0, 1.0)
        self.d_stop = 0.05  # m
        self.d_at_obs = 0.25  # m: an IR distance under this is "at an obstacle"
        self.d_unsafe = 0.10  # m: under this, "unsafe"

        # True: blend until at the goal; False: switch between the controllers (the block in execute)
        self.is_blending = True

    def execute(self, dt):
        """One step: odometry, pick the state (blending or switching), the controller, ensure_w, speeds."""
        self.update_odometry()

        inputs = self.inputs()

        if self.is_blending:
            # blend until the robot is at the goal
            if self.check_event("at_goal"):
                self.switch_to_state("stop")
            else:
                self.switch_to_state("ao_and_gtg")
        else:
            # Switch between the controllers: at the goal stop; too close to an obstacle, only avoid it;
            # near one, blend; in free space, go to the goal.
            # START CODE BLOCK
            # TODO (week 5, part 2): pick this step's state with self.check_event(...) and
            # self.switch_to_state(...): at the goal ("at_goal") stop; "unsafe": avoid_obstacles;
            # "at_obstacle": ao_and_gtg; otherwise go_to_goal. Until then the robot stays put.
            self.switch_to_state("stop")
            # END CODE BLOCK

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
