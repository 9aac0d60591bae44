"""Differential drive (week 1): nothing to do yet.

Week 2 asks you to turn a unicycle command (v, w) into wheel speeds; until then the wheels stay still.
This week has no code blocks.
"""


def uni_to_diff(robot, v, w):
    """Wheel angular speeds (vel_r, vel_l) for (v, w): week 2 writes this; for now the wheels stay still."""
    vel_r = 0
    vel_l = 0
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
