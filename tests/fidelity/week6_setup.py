"""Week 6 described for the loader and LocalBrain until the course's week table declares it.

`WEEK6` lists the week's student files (week 4's, the week-5 AOandGTG, the new follow_wall.py) and the
names each must define; the robot is the week-4 QuickBot, the world the week-4 L with the arena walls.
"""

from __future__ import annotations

from simiam.course.week import SupervisorSettings, Week
from simiam.robot.quickbot import MAX_VEL_130RPM, MIN_VEL_30RPM, RobotSpec

WEEK6 = Week(
    number=6,
    title="follow a wall",
    spec=RobotSpec(week=6, max_vel=MAX_VEL_130RPM, min_vel=MIN_VEL_30RPM, ir_mode="week3"),
    checks="grader.checks.week6",
    world="week6",
    student_files=("differential_drive.py", "quickbot.py", "go_to_angle.py", "go_to_goal.py",
                   "avoid_obstacles.py", "ao_and_gtg.py", "follow_wall.py", "qb_supervisor.py"),
    required_names={
        "differential_drive.py": ("uni_to_diff", "diff_to_uni"),
        "quickbot.py": ("get_ir_distances",),
        "go_to_angle.py": ("GoToAngle",),
        "go_to_goal.py": ("GoToGoal", "GoToGoal.execute"),
        "avoid_obstacles.py": (
            "AvoidObstacles", "AvoidObstacles.execute", "AvoidObstacles.apply_sensor_geometry",
            "AvoidObstacles.get_transformation_matrix",
        ),
        "ao_and_gtg.py": ("AOandGTG", "AOandGTG.execute"),
        "follow_wall.py": ("FollowWall", "FollowWall.execute"),
        "qb_supervisor.py": ("QBSupervisor", "QBSupervisor.execute", "QBSupervisor.update_odometry",
                             "QBSupervisor.ensure_w"),
    },
    settings=SupervisorSettings(v=0.15, state="follow_wall", extra={"d_fw": 0.18, "fw_direction": "left"}),
    seconds=90.0,
    dt=0.05,
)
