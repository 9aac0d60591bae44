"""The simulated QuickBot: robot spec, IR sensor model, wheel encoders, kinematics. It knows nothing of the
course: a week's robot is the week's declaration (`simiam.course.weeks.spec_for_week`)."""

from simiam.robot.quickbot import RobotSpec, limit_speeds

__all__ = ["RobotSpec", "limit_speeds"]
