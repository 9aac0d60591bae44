"""Wrong placeholders kept as test data: tests/course/test_stubs.py must reject each one."""

from simiam.course.placeholders import Placeholder

# forgets vel_l, which the code after the block returns
MISSING_NAME = Placeholder("differential_drive.py", "uni_to_diff", week=2, hint="x", code="vel_r = 0")
# forgets self.Kd, which execute reads
MISSING_ATTRIBUTE = Placeholder(
    "go_to_goal.py", "GoToGoal.__init__", week=3, hint="x", code="self.Kp = 0\nself.Ki = 0", tunable=True
)
# does not parse
BROKEN = Placeholder("go_to_goal.py", "GoToGoal.execute", week=3, occurrence=2, hint="x", code="e_k = (0")
# no hint for the student
NO_HINT = Placeholder("go_to_goal.py", "GoToGoal.execute", week=3, occurrence=2, hint="", code="e_k = 0")

WRONG = [MISSING_NAME, MISSING_ATTRIBUTE, BROKEN, NO_HINT]
