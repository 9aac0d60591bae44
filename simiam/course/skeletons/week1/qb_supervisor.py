"""QBSupervisor for week 1: the robot stands still (the Stop controller runs).

Week 1 asks only that the simulator runs. This week has no code blocks.
"""

from simiam.control import Stop, Supervisor


class QBSupervisor(Supervisor):
    """Runs the Stop controller: the robot does not move."""

    def __init__(self):
        super().__init__()
        self.add_controller(Stop())
        self.switch_to_state("stop")

    def execute(self, dt):
        """One step: the controller, the wheel speeds, then odometry."""
        inputs = self.inputs()
        v, w = self.execute_controller(inputs, dt)

        vel_r, vel_l = self.robot.dynamics.uni_to_diff(self.robot, v, w)
        self.robot.set_wheel_speeds(vel_r, vel_l)

        self.update_odometry()

    def update_odometry(self):
        """Week 2 writes the odometry; for now the estimate stays at the start pose."""
