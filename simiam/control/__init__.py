"""On the robot: what student code builds on (Pose2D, RobotView, Supervisor, Controller, Stop, Inputs,
norm).

`LocalBrain` (simiam.control.local_brain) runs a loaded submission against the simulator in-process.
"""

from simiam.control.controller import Controller, Inputs
from simiam.control.norm import norm
from simiam.control.pose import Pose2D
from simiam.control.robot_view import RobotView
from simiam.control.stop import Stop
from simiam.control.supervisor import Supervisor, WheelTicks

__all__ = ["Controller", "Inputs", "Pose2D", "RobotView", "Stop", "Supervisor", "WheelTicks", "norm"]
