"""Week 7 of the course: navigation with the full hybrid automaton (go to the goal, avoid obstacles, their
blend, follow walls out of a trap; the sliding test and progress toward the goal).

The world is the original's final one: a U-shaped trap around the start, open away from the goal, and an
L near the goal (1.1, 1.1). The time step is the course simulator's 0.05 s, the one the original's test 7.1
stepped with (at 0.033 s the course's own solution stops 0.052 m from the release goal).
"""

from __future__ import annotations

from dataclasses import replace

from simiam.course.placeholders import Placeholder
from simiam.course.week import SupervisorSettings, Week
from simiam.course.weeks.week4 import WEEK as WEEK4

# The blocks new this week, all in qb_supervisor.py: what the stub holds instead of the solution's body.
BLOCKS = (
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.__init__",
        occurrence=2,
        hint="""Week 7, the thresholds of the events: an IR distance under d_at_obs (m) is "at an obstacle",
under d_unsafe "unsafe". These are the course's starting values; tune them with the automaton.""",
        code="self.d_at_obs = 0.10\nself.d_unsafe = 0.05",
        tunable=True,
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.execute",
        hint="""TODO (week 7, part 3): the automaton. Each step pick the state from the events
(self.check_event(name)) with self.switch_to_state(name): at_goal -> stop; unsafe ->
avoid_obstacles; going to the goal with progress_made -> self.set_progress_point() and keep
going; no progress and at_obstacle -> set self.fw_direction ("left" or "right", the side of
the obstacle) and follow_wall; following a wall, progress_made and not sliding on that side
(sliding_left / sliding_right) -> go_to_goal. Until then the robot drives to the goal.""",
        code=('if self.check_event("at_goal"):\n    self.switch_to_state("stop")\n'
              'self.fw_direction = ""  # no wall to follow'),
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.set_progress_point",
        hint="""TODO (week 7, part 1): remember how close to the goal the robot has come: self.d_prog
becomes the distance from the estimate (x, y) to self.goal if that is smaller.
Until then d_prog stays at its start, 10 m.""",
        code="self.d_prog = self.d_prog",
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.progress_made",
        hint="""TODO (week 7, part 1): progress = True when the estimate (x, y) is closer to self.goal
than self.d_prog, the closest point so far (the manual allows a slack: closer than
d_prog - epsilon with epsilon = 0.1). Until then there is always progress.""",
        code="progress = True",
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.sliding_left",
        hint="""TODO (week 7, part 2): sigma = the two numbers with [u_gtg u_ao] sigma = u_fw (u_gtg and
u_ao are the columns of a 2x2 matrix). The robot slides along the wall while both are
positive. When u_gtg and u_ao are parallel (at the goal u_gtg is zero) the matrix is
singular: do not let that stop the run. Until then sigma is 0: never sliding.""",
        code="sigma = np.zeros(2)",
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.sliding_right",
        hint="""TODO (week 7, part 2): the same test as sliding_left, with u_fw of a wall on the right.""",
        code="sigma = np.zeros(2)",
    ),
)

_FILES = ("differential_drive.py", "quickbot.py", "go_to_angle.py", "go_to_goal.py", "avoid_obstacles.py",
          "ao_and_gtg.py", "follow_wall.py", "sliding_mode.py", "qb_supervisor.py")

WEEK = Week(
    number=7,
    title="navigation: the full automaton (follow walls out of a trap, sliding, progress)",
    spec=replace(WEEK4.spec, week=7),
    world="final",
    student_files=_FILES,
    required_names={
        **{f: names for f, names in WEEK4.required_names.items() if f != "qb_supervisor.py"},
        "ao_and_gtg.py": ("AOandGTG", "AOandGTG.execute"),
        "follow_wall.py": ("FollowWall", "FollowWall.execute"),
        "sliding_mode.py": ("SlidingMode", "SlidingMode.execute"),
        "qb_supervisor.py": ("QBSupervisor", "QBSupervisor.execute", "QBSupervisor.update_odometry",
                             "QBSupervisor.ensure_w", "QBSupervisor.set_progress_point",
                             "QBSupervisor.progress_made", "QBSupervisor.sliding_left",
                             "QBSupervisor.sliding_right", "QBSupervisor.sliding_vectors"),
    },
    checks="grader.checks.week7",
    blocks=BLOCKS,
    settings=SupervisorSettings(v=0.15, goal=(1.1, 1.1), d_stop=0.05),
    seconds=60.0,
    dt=0.05,
    # the automaton's trace: the state (always recorded), each event as checked in the step, the switches
    debug_signals=("v", "w", "theta_g", "u_ao", "u_gtg", "u_fw_t", "u_fw_p", "ir_points_wf", "fw_direction",
                   "d_prog", "switches", "at_goal", "at_obstacle", "unsafe", "obstacle_cleared",
                   "progress_made", "sliding_left", "sliding_right", "sigma_left", "sigma_right"),
    hidden_variants="other goals and start headings in the trap world",
    summary=("goal", "switches"),
)
