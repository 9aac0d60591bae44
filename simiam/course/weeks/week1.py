"""Week 1 of the course: the simulator, the robot and its files (nothing to write; the robot stays still).

Week 1's simulator runs the supervisor before it moves the robot (`brain_first`), as the original's
week-1 branch did.
"""

from __future__ import annotations

from simiam.course.week import SupervisorSettings, Week
from simiam.robot.quickbot import MAX_VEL_80RPM, RobotSpec
from simiam.signals import WEEKS_1_TO_4

WEEK = Week(
    number=1,
    title="the simulator, the robot and its files (nothing to write; the robot stays still)",
    spec=RobotSpec(week=1, max_vel=MAX_VEL_80RPM, min_vel=0.0, ir_mode="week2", brain_first=True),
    world="week1",
    student_files=("differential_drive.py", "quickbot.py", "qb_supervisor.py"),
    required_names={
        "differential_drive.py": ("uni_to_diff", "diff_to_uni"),
        "quickbot.py": ("get_ir_distances",),
        "qb_supervisor.py": ("QBSupervisor", "QBSupervisor.execute", "QBSupervisor.update_odometry"),
    },
    checks="grader.checks.week1",
    settings=SupervisorSettings(),
    seconds=3.0,
    debug_signals=WEEKS_1_TO_4,  # all five, as every trace of weeks 1-4 has carried them
    summary=("path",),
)
