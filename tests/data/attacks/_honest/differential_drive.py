"""Honest week 1 differential drive: the base every attack overlays."""


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    vel_r = (2 * v + w * L) / (2 * R)
    vel_l = (2 * v - w * L) / (2 * R)
    return vel_r, vel_l


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


def attack(**args):
    return uni_to_diff(_Robot(), 0.1, 0.5)


class _Robot:
    wheel_radius = 0.0325
    wheel_base_length = 0.09925
