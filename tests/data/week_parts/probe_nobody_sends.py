"""Wrong: two probes no check sends; the second does not say what student code it runs."""

from grader.inside.probing import exercises, plain, robot_for


@exercises("go_to_goal.py:GoToGoal.execute")
def week3_heading(sub, week: int) -> object:
    return plain(sub.module("go_to_goal").GoToGoal().theta_g)


def week3_speeds(sub, week: int, v: float, w: float) -> object:
    return plain(sub.module("differential_drive").uni_to_diff(robot_for(sub, week), v, w))
