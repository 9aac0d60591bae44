"""A wrong version kept for tests/course/test_weeks.py: week 6's declaration as a week 9, with the wall's
side misspelt in `extra` ("fw_directon"). Accepted, a run would set it on the supervisor and nothing would
read it: the robot would follow the wall on whichever side the student's __init__ chose."""

import dataclasses

from simiam.course.week import SupervisorSettings
from simiam.course.weeks.week6 import WEEK as _WEEK6

WEEK = dataclasses.replace(
    _WEEK6, number=9, spec=dataclasses.replace(_WEEK6.spec, week=9),
    settings=SupervisorSettings(v=0.15, state="follow_wall", extra={"fw_directon": "left"}),
)
