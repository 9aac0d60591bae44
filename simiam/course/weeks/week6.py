"""Week 6 of the course: follow a wall (FollowWall: two IR points make the wall, steer along it at d_fw).

The robot and the world are week 4's (130/30 rpm; the arena walls and the L-shaped obstacle). The supervisor
always runs FollowWall, on the side `fw_direction` at the distance `d_fw` the student sets.
"""

from __future__ import annotations

from simiam.course.placeholders import Placeholder
from simiam.course.week import SupervisorSettings, Week
from simiam.laps import Gate
from simiam.robot.quickbot import MAX_VEL_130RPM, MIN_VEL_30RPM, RobotSpec

# The blocks new this week: what the stub holds instead of the solution's body.
BLOCKS = (
    Placeholder(
        "follow_wall.py",
        "FollowWall.execute",
        hint="""TODO (week 6): estimate the wall from two IR points and steer along it at d_fw.
1. p_1, p_2 = the points (ir_distances_wf[0:2, i]) of the two sensors on the side `direction`
   with the shortest distances: sensors 0, 1, 2 for "left", 4, 3, 2 for "right" (on a tie,
   the first in that order). p_1 is the lower index for "left", the higher for "right".
2. u_fw_t = p_2 - p_1, along the wall; u_fw_tp = u_fw_t / |u_fw_t|.
3. u_a = p_1, u_p = (x, y); u_fw_p = (u_a - u_p) - ((u_a - u_p) . u_fw_tp) * u_fw_tp,
   from the robot to the nearest point of the wall (its length is the distance to it).
4. u_fw_pp = u_fw_p - d_fw * u_fw_p / |u_fw_p|, zero when the robot is d_fw from the wall.
5. u_fw = d_fw * u_fw_tp + u_fw_pp. Until then u_fw is zero and the robot heads along x.""",
        code=(
            "p_1 = ir_distances_wf[0:2, 0]\np_2 = ir_distances_wf[0:2, 0]\nu_fw_t = np.zeros(2)\n"
            "u_fw_tp = np.zeros(2)\nu_a = p_1\nu_p = np.array([x, y])\nu_fw_p = np.zeros(2)\n"
            "u_fw_pp = np.zeros(2)\nu_fw = np.zeros(2)"
        ),
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.__init__",
        hint="""TODO (week 6): d_fw = the distance (m) to keep from the wall, which the IR sensors must
see (they read 0.04 to 0.3 m); fw_direction = the side of the wall, "left" or "right".
Until then d_fw is 0 and the robot drives into the wall.""",
        code='self.d_fw = 0\nself.fw_direction = "left"',
    ),
)

WEEK = Week(
    number=6,
    title="follow a wall (two IR points make the wall; steer along it at d_fw)",
    spec=RobotSpec(week=6, max_vel=MAX_VEL_130RPM, min_vel=MIN_VEL_30RPM, ir_mode="week3"),
    world="week6",
    student_files=("differential_drive.py", "quickbot.py", "go_to_angle.py", "go_to_goal.py",
                   "avoid_obstacles.py", "ao_and_gtg.py", "follow_wall.py", "qb_supervisor.py"),
    required_names={
        "differential_drive.py": ("uni_to_diff", "diff_to_uni"),
        "quickbot.py": ("get_ir_distances",),
        "go_to_angle.py": ("GoToAngle",),
        "go_to_goal.py": ("GoToGoal", "GoToGoal.execute"),
        "avoid_obstacles.py": (
            "AvoidObstacles",
            "AvoidObstacles.execute",
            "AvoidObstacles.apply_sensor_geometry",
            "AvoidObstacles.get_transformation_matrix",
        ),
        "ao_and_gtg.py": ("AOandGTG", "AOandGTG.execute"),
        "follow_wall.py": ("FollowWall", "FollowWall.execute"),
        "qb_supervisor.py": ("QBSupervisor", "QBSupervisor.execute", "QBSupervisor.update_odometry",
                             "QBSupervisor.ensure_w"),
    },
    checks="grader.checks.week6",
    blocks=BLOCKS,
    # the original test 6.1: v 0.15, the wall on the left; d_fw is the student's own
    settings=SupervisorSettings(v=0.15, state="follow_wall", extra={"fw_direction": "left"}),
    seconds=90.0,
    dt=0.05,
    debug_signals=("v", "w", "theta_g", "ir_points_wf", "u_fw", "u_fw_t", "u_fw_p", "u_fw_pp",
                   "fw_direction"),
    hidden_variants="either side, other start headings and distances d_fw",
    summary=("path",),
    # from the L's lower block (y = 0.2) straight down to the bottom wall (y = -1.4), through the start
    # (0, 0): following the wall on the left (the run above) the robot goes round the L anticlockwise and
    # crosses it toward +x; on the right clockwise, the other way (the checks' gate("right"))
    lap_gate=Gate(x=0.0, y_low=-1.4, y_high=0.2, sign=1),
)
