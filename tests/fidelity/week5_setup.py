"""Week 5 described for the loader and LocalBrain until the course's week table declares it: the week-4
QuickBot, the week-5 world, ao_and_gtg.py among the student files."""

from __future__ import annotations

from simiam.course.week import SupervisorSettings, Week
from simiam.course.weeks import get_week
from simiam.robot.quickbot import MAX_VEL_130RPM, MIN_VEL_30RPM, RobotSpec

_WEEK4 = get_week(4)

WEEK5 = Week(
    number=5,
    title="blend and switch between go-to-goal and avoid-obstacles",
    spec=RobotSpec(week=5, max_vel=MAX_VEL_130RPM, min_vel=MIN_VEL_30RPM, ir_mode="week3"),
    world="week5",
    student_files=_WEEK4.student_files[:-1] + ("ao_and_gtg.py", "qb_supervisor.py"),
    required_names={**_WEEK4.required_names, "ao_and_gtg.py": ("AOandGTG", "AOandGTG.execute")},
    checks="grader.checks.week5",
    settings=SupervisorSettings(v=0.15, goal=(1.0, 1.0), d_stop=0.05, state="ao_and_gtg"),
    seconds=60.0,
)
