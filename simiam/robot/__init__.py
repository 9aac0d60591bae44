"""The simulated QuickBot: robot spec per week, IR sensor model, wheel encoders, kinematics."""

from simiam.robot.quickbot import RobotSpec, limit_speeds, spec_for_week

__all__ = ["RobotSpec", "limit_speeds", "spec_for_week"]
