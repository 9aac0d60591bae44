"""Week 2 of the course: kinematics, IR distances and odometry; go to an angle.
"""

from __future__ import annotations

import math

from simiam.course.placeholders import Placeholder
from simiam.course.week import SupervisorSettings, Week
from simiam.robot.quickbot import MAX_VEL_80RPM, RobotSpec
from simiam.signals import WEEKS_1_TO_4

# The blocks new this week: what the stub holds instead of the solution's body.
BLOCKS = (
    Placeholder(
        "differential_drive.py",
        "uni_to_diff",
        hint="""TODO (week 2): turn the unicycle command (v in m/s, w in rad/s) into the angular speeds
of the right and left wheels, vel_r and vel_l (rad/s). R is the wheel radius and L the
distance between the wheels (manual, section 2.2). Until then the wheels do not turn.""",
        code="vel_r = 0\nvel_l = 0",
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.update_odometry",
        hint="""TODO (week 2): estimate how the pose changed since the last call.
A wheel covered (its ticks now - its ticks then) * m_per_tick metres. From the right and
left distances, L and theta, compute x_dt, y_dt and theta_dt. Until then the estimate
never leaves the start pose.""",
        code="x_dt = 0\ny_dt = 0\ntheta_dt = 0",
    ),
    Placeholder(
        "quickbot.py",
        "get_ir_distances",
        hint="""TODO (week 2): raw ADC values -> volts (this week's divider: raw / 500), then coeff,
the degree-5 polynomial (highest power first) fitted once to the table of Figure 2b with
numpy.polyfit(voltages, distances, 5), pasted here as numbers. Until then every distance
reads 0.""",
        code="ir_voltages = ir_array_values\ncoeff = [0, 0, 0, 0, 0, 0]",
        revised_in=(3,),
        revised_why="the IR sensors report a different raw value from week 3 (new divider and fit)",
    ),
)

WEEK = Week(
    number=2,
    title="kinematics, IR distances and odometry; go to an angle",
    spec=RobotSpec(week=2, max_vel=MAX_VEL_80RPM, min_vel=0.0, ir_mode="week2"),
    world="week2",
    student_files=("differential_drive.py", "quickbot.py", "go_to_angle.py", "qb_supervisor.py"),
    required_names={
        "differential_drive.py": ("uni_to_diff", "diff_to_uni"),
        "quickbot.py": ("get_ir_distances",),
        "go_to_angle.py": ("GoToAngle",),
        "qb_supervisor.py": ("QBSupervisor", "QBSupervisor.execute", "QBSupervisor.update_odometry"),
    },
    checks="grader.checks.week2",
    blocks=BLOCKS,
    settings=SupervisorSettings(theta_d=math.pi / 4, v=0.1),
    seconds=8.0,
    debug_signals=WEEKS_1_TO_4,  # all five, as every trace of weeks 1-4 has carried them
    hidden_variants="other angles theta_d",
    summary=("heading",),
)
