"""Attack: close the grader's channel, stop itself with SIGSTOP, or ignore SIGTERM and keep running."""
import os
import signal


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


def attack(kind='close', **args):
    if kind == 'close':
        for fd in range(3, 64):
            try:
                os.close(fd)
            except OSError:
                pass
        return 'closed'
    if kind == 'stop':
        os.kill(os.getpid(), signal.SIGSTOP)
        return 'resumed'
    if kind == 'ignore_term':
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        while True:
            pass
    raise ValueError(kind)
