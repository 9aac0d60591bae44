"""Week 5 described for the loader and LocalBrain, until the declared-week API holds it (simiam.course.weeks
knows weeks 1-4 only): the week-4 robot, the week-5 world, and ao_and_gtg.py among the student files."""

from __future__ import annotations

from simiam.course.weeks import WeekConfig, week_config

_WEEK4 = week_config(4)

WEEK5 = WeekConfig(
    number=5,
    world="week5",
    student_files=_WEEK4.student_files[:-1] + ("ao_and_gtg.py", "qb_supervisor.py"),
    required_names={
        **_WEEK4.required_names,
        "ao_and_gtg.py": ("AOandGTG", "AOandGTG.execute"),
    },
    default_settings={"v": 0.15, "goal": (1.0, 1.0), "d_stop": 0.05, "state": "ao_and_gtg"},
    seconds=60.0,
    dt=0.05,
)
