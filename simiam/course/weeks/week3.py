"""Week 3 of the course: go to goal (PID on the heading) and ensure_w.

From this week the IR sensors use the week-3 divider (raw = round(1000*V/3)).
"""

from __future__ import annotations

from simiam.course.placeholders import Placeholder
from simiam.course.week import SupervisorSettings, Week
from simiam.robot.quickbot import MAX_VEL_80RPM, RobotSpec
from simiam.signals import WEEKS_1_TO_4

# The blocks new this week: what the stub holds instead of the solution's body.
BLOCKS = (
    Placeholder(
        "go_to_goal.py",
        "GoToGoal.__init__",
        hint="""TODO (week 3, part 3): tune the PID gains so that theta settles on theta_g within 10%
in 3 s or less, overshooting by 10% at most. With zero gains the robot never turns.""",
        code="self.Kp = 0\nself.Ki = 0\nself.Kd = 0",
        tunable=True,
    ),
    Placeholder(
        "go_to_goal.py",
        "GoToGoal.execute",
        occurrence=1,
        hint="""TODO (week 3, part 1): u_x, u_y = the vector from the robot (x, y) to the goal
(x_g, y_g); theta_g = the angle it makes with the x axis (math.atan2).""",
        code="u_x = 0\nu_y = 0\ntheta_g = 0",
    ),
    Placeholder(
        "go_to_goal.py",
        "GoToGoal.execute",
        occurrence=2,
        hint="""TODO (week 3, part 2): e_k = theta_g - theta, brought back into [-pi, pi]
(the atan2 of its sine and cosine does that).""",
        code="e_k = 0",
    ),
    Placeholder(
        "go_to_goal.py",
        "GoToGoal.execute",
        occurrence=3,
        hint="""TODO (week 3, part 3): e_P is this step's error; e_I adds e_k * dt to the error
accumulated so far (self.E_k); e_D is the change since the last step's error
(self.e_k_1) divided by dt. The code below stores e_I and e_k for the next step.""",
        code="e_P = 0\ne_I = 0\ne_D = 0",
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.ensure_w",
        hint="""TODO (week 3, part 4): if the faster wheel would turn faster than robot.max_vel, take
the excess off both wheels; if the slower one would turn backwards faster than max_vel,
add the shortfall to both. The same shift on both wheels keeps w and gives up some v.
Until then the speeds pass through unchanged (w is lost when a motor saturates).""",
        code="vel_r = vel_r_d\nvel_l = vel_l_d",
    ),
)

WEEK = Week(
    number=3,
    title="go to goal (PID on the heading) and ensure_w",
    spec=RobotSpec(week=3, max_vel=MAX_VEL_80RPM, min_vel=0.0, ir_mode="week3"),
    world="week3",
    student_files=("differential_drive.py", "quickbot.py", "go_to_angle.py", "go_to_goal.py",
                   "qb_supervisor.py"),
    required_names={
        "differential_drive.py": ("uni_to_diff", "diff_to_uni"),
        "quickbot.py": ("get_ir_distances",),
        "go_to_angle.py": ("GoToAngle",),
        "go_to_goal.py": ("GoToGoal", "GoToGoal.execute"),
        "qb_supervisor.py": ("QBSupervisor", "QBSupervisor.execute", "QBSupervisor.update_odometry",
                             "QBSupervisor.ensure_w"),
    },
    checks="grader.checks.week3",
    blocks=BLOCKS,
    settings=SupervisorSettings(v=0.2, goal=(-1.0, 1.0), d_stop=0.05),
    seconds=30.0,
    debug_signals=WEEKS_1_TO_4,  # all five, as every trace of weeks 1-4 has carried them
    hidden_variants="other goals",
    summary=("goal",),
)
