"""Honest week 1 supervisor: the robot stays still."""


class QBSupervisor:
    def __init__(self, *args, **kwargs):
        pass

    def execute(self, robot, state_estimate, dt):
        robot.set_wheel_speeds(0, 0)

    def update_odometry(self):
        pass
