"""Week 5 of the course: blend and switch between going to the goal and avoiding obstacles.

The sp14 release: AOandGTG blends u_gtg and u_ao as they are (not normalised) with alpha 0.25; the
supervisor's events look at all five IR sensors with d_at_obs 0.25 m and d_unsafe 0.10 m; the run starts in
ao_and_gtg (the robot starts 0.15 m from the block, already "at an obstacle").
"""

from __future__ import annotations

from simiam.course.placeholders import Placeholder
from simiam.course.week import SupervisorSettings, Week
from simiam.course.weeks.week4 import WEEK as WEEK4
from simiam.robot.quickbot import MAX_VEL_130RPM, MIN_VEL_30RPM, RobotSpec

# The blocks new this week: what the stub holds instead of the solution's body.
BLOCKS = (
    Placeholder(
        "ao_and_gtg.py",
        "AOandGTG.execute",
        hint="""TODO (week 5, part 1): u_ao_gtg = a blend of u_gtg (from the robot to the goal) and u_ao
(away from the obstacles), both 2-vectors (numpy arrays): alpha * u_gtg + (1 - alpha) * u_ao
with 0 < alpha < 1 lies between them. You may normalise both first (np.linalg.norm; mind a
zero vector). Until then the heading is 0: the robot turns to face the x axis.""",
        code="u_ao_gtg = np.zeros(2)",
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.execute",
        hint="""TODO (week 5, part 2): pick this step's state with self.check_event(...) and
self.switch_to_state(...): at the goal ("at_goal") stop; "unsafe": avoid_obstacles;
"at_obstacle": ao_and_gtg; otherwise go_to_goal. Until then the robot stays put.""",
        code='self.switch_to_state("stop")',
    ),
)

WEEK = Week(
    number=5,
    title="blend and switch between going to the goal and avoiding obstacles",
    spec=RobotSpec(week=5, max_vel=MAX_VEL_130RPM, min_vel=MIN_VEL_30RPM, ir_mode="week3"),
    world="week5",
    student_files=(*WEEK4.student_files[:-1], "ao_and_gtg.py", "qb_supervisor.py"),
    required_names={**WEEK4.required_names, "ao_and_gtg.py": ("AOandGTG", "AOandGTG.execute")},
    checks="grader.checks.week5",
    blocks=BLOCKS,
    settings=SupervisorSettings(v=0.15, goal=(1.0, 1.0), d_stop=0.05, state="ao_and_gtg"),
    seconds=60.0,
    debug_signals=("v", "w", "theta_g", "u_ao", "ir_points_wf", "u_gtg", "u_ao_gtg", "switches", "at_goal",
                   "at_obstacle", "unsafe", "obstacle_cleared"),
    hidden_variants="other start poses and goals, blending and switching",
    summary=("goal", "switches"),
)
