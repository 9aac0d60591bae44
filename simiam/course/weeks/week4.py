"""Week 4 of the course: avoid obstacles (IR points in the world frame, weighted sum).

From this week the motors run at 130 rpm with a 30 rpm dead zone (sp14's QuickBot).
"""

from __future__ import annotations

from simiam.course.placeholders import Placeholder
from simiam.course.week import SupervisorSettings, Week
from simiam.robot.quickbot import MAX_VEL_130RPM, MIN_VEL_30RPM, RobotSpec
from simiam.signals import WEEKS_1_TO_4

# The blocks new this week: what the stub holds instead of the solution's body.
BLOCKS = (
    Placeholder(
        "avoid_obstacles.py",
        "AvoidObstacles.__init__",
        hint="""Week 4: the PID gains that steer along u_ao. These values work; tune them if you like.""",
        code="self.Kp = 4\nself.Ki = 0.01\nself.Kd = 0.1",
        tunable=True,
    ),
    Placeholder(
        "avoid_obstacles.py",
        "AvoidObstacles.execute",
        hint="""TODO (week 4, part 3): sensor_gains = one weight per sensor, the same on the left and
the right; u_i = column i is sensor_gains[i] times the vector from the robot (x, y) to
the IR point ir_distances_wf[:, i]; u_ao = the sum of the columns; theta_ao = its angle;
e_k = theta_ao - theta, kept in [-pi, pi]. Until then the robot drives straight.""",
        code=(
            "sensor_gains = [0, 0, 0, 0, 0]\nu_i = np.zeros((2, 5))\nu_ao = np.sum(u_i, axis=1)\n"
            "theta_ao = 0\ne_k = 0"
        ),
    ),
    Placeholder(
        "avoid_obstacles.py",
        "AvoidObstacles.apply_sensor_geometry",
        hint="""TODO (week 4, parts 1 and 2): sensor i measured the point (ir_distances[i], 0) in its
own frame. Move it into the robot's frame with the sensor's mount pose
(robot.ir_array[i].location: x_s, y_s, theta_s), then into the world with the estimate
(x, y, theta), both with get_transformation_matrix. Column i of ir_distances_rf and of
ir_distances_wf holds that point as (x, y, 1).""",
        code="ir_distances_rf = np.zeros((3, 5))\nir_distances_wf = np.zeros((3, 5))",
    ),
    Placeholder(
        "avoid_obstacles.py",
        "AvoidObstacles.get_transformation_matrix",
        hint="""TODO (week 4, part 1): T = the 3x3 matrix that rotates a point (x, y, 1) by theta,
then translates it by (x, y).""",
        code="T = np.zeros((3, 3))",
    ),
)

WEEK = Week(
    number=4,
    title="avoid obstacles (IR points in the world frame, weighted sum)",
    spec=RobotSpec(week=4, max_vel=MAX_VEL_130RPM, min_vel=MIN_VEL_30RPM, ir_mode="week3"),
    world="week4",
    student_files=("differential_drive.py", "quickbot.py", "go_to_angle.py", "go_to_goal.py",
                   "avoid_obstacles.py", "qb_supervisor.py"),
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
        "qb_supervisor.py": ("QBSupervisor", "QBSupervisor.execute", "QBSupervisor.update_odometry",
                             "QBSupervisor.ensure_w"),
    },
    checks="grader.checks.week4",
    blocks=BLOCKS,
    # v: the original's 0.9 is capped by ensure_w and crashes its own AvoidObstacles
    settings=SupervisorSettings(v=0.15, state="avoid_obstacles"),
    seconds=60.0,
    debug_signals=WEEKS_1_TO_4,  # all five, as every trace of weeks 1-4 has carried them
    hidden_variants="the week-4 world mirrored and turned about the start",
    summary=("goal",),
)
