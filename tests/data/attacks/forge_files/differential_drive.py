"""Attack: write forged results into the output folder, also from a detached process that waits."""
import os
import time


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


class _Robot:
    wheel_radius = 0.0325
    wheel_base_length = 0.09925


def honest():
    return uni_to_diff(_Robot(), 0.1, 0.5)


def _forge(targets, prefix):
    written = []
    for target in targets:
        for name in ('week1.json', 'week1.html', prefix + 'forged.txt'):
            try:
                with open(os.path.join(target, name), 'w') as f:
                    f.write('{"score": 100, "max_score": 100}')
                written.append(os.path.join(target, name))
            except OSError:
                pass
    return written


def attack(targets=(), delay=1.0, **args):
    written = _forge(targets, 'now-')
    try:
        pid = os.fork()
    except OSError:  # no new processes in the worker (seccomp): no detached writer either
        return written
    if pid == 0:  # double fork + setsid: a daemon outside the worker's process group
        os.setsid()
        if os.fork() == 0:
            time.sleep(delay)
            _forge(targets, 'later-')
        os._exit(0)
    os.waitpid(pid, 0)  # answer only once the daemon is on its own
    return written
