"""Differential drive: unicycle (v, w) <-> the wheels' angular speeds (vel_r, vel_l).

The robot is steered with a linear velocity v (m/s) and an angular velocity w (rad/s); the motors take
the angular speeds of the right and left wheels (rad/s). R is the wheel radius, L the distance between
the wheels (the manual, section 2.2).

Student block (week 2) and the placeholder the stub gets:
  uni_to_diff: vel_r, vel_l from v, w, R, L.   Placeholder: `vel_r = 0` and `vel_l = 0` (robot stays still).
"""


def uni_to_diff(robot, v, w):
    """Wheel angular speeds (vel_r, vel_l) in rad/s that drive the robot with (v, w)."""
    R = robot.wheel_radius
    L = robot.wheel_base_length

    # START CODE BLOCK
    vel_r = (2 * v + w * L) / (2 * R)
    vel_l = (2 * v - w * L) / (2 * R)
    # END CODE BLOCK

    return vel_r, vel_l


def diff_to_uni(robot, vel_r, vel_l):
    """The (v, w) the robot moves with when its wheels turn at (vel_r, vel_l) rad/s."""
    R = robot.wheel_radius
    L = robot.wheel_base_length
    # any real number: a numpy bool, say, cannot be subtracted
    vel_r, vel_l = float(vel_r), float(vel_l)

    v = R / 2 * (vel_r + vel_l)
    w = R / L * (vel_r - vel_l)

    return v, w
