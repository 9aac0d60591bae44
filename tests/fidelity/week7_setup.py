"""Week 7 described for the loader and LocalBrain until the course declares it (simiam.course.weeks).

The files and names are those of solutions/week7; the world is the original's final world (the trap
around the start), the robot the week-4 QuickBot (130/30 rpm, the dead zone).
"""

from __future__ import annotations

from simiam.course.weeks import WeekConfig

STUDENT_FILES = (
    "differential_drive.py",
    "quickbot.py",
    "go_to_angle.py",
    "go_to_goal.py",
    "avoid_obstacles.py",
    "ao_and_gtg.py",
    "follow_wall.py",
    "sliding_mode.py",
    "qb_supervisor.py",
)

WEEK7 = WeekConfig(
    number=7,
    world="final",
    student_files=STUDENT_FILES,
    required_names={
        "differential_drive.py": ("uni_to_diff", "diff_to_uni"),
        "quickbot.py": ("get_ir_distances",),
        "go_to_angle.py": ("GoToAngle",),
        "go_to_goal.py": ("GoToGoal", "GoToGoal.execute"),
        "avoid_obstacles.py": ("AvoidObstacles", "AvoidObstacles.execute"),
        "ao_and_gtg.py": ("AOandGTG", "AOandGTG.execute"),
        "follow_wall.py": ("FollowWall", "FollowWall.execute"),
        "sliding_mode.py": ("SlidingMode", "SlidingMode.execute"),
        "qb_supervisor.py": (
            "QBSupervisor",
            "QBSupervisor.execute",
            "QBSupervisor.update_odometry",
            "QBSupervisor.ensure_w",
            "QBSupervisor.progress_made",
            "QBSupervisor.set_progress_point",
            "QBSupervisor.sliding_left",
            "QBSupervisor.sliding_right",
        ),
    },
    default_settings={"v": 0.15, "goal": (1.1, 1.1), "d_stop": 0.05},
    seconds=60.0,
    dt=0.05,
)
