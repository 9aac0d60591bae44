"""Attack: leave System V shared memory and a message queue, a POSIX shared-memory file and files in the
machine's shared writable folders behind, to outlive the grading (and be found by the next student)."""

import ctypes
import os


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


def attack(key=0x5157AB01, tag='simiam-leftover', **args):
    left = {'sysv': [], 'files': []}
    libc = ctypes.CDLL(None, use_errno=True)
    ipc_creat = 0o1000
    if libc.shmget(key, 4096, ipc_creat | 0o666) >= 0:
        left['sysv'].append(['shm', key])
    if libc.msgget(key + 1, ipc_creat | 0o666) >= 0:
        left['sysv'].append(['msg', key + 1])
    for folder in ('/dev/shm', '/tmp', '/var/tmp'):
        path = os.path.join(folder, f'{tag}-{os.getpid()}')
        try:
            with open(path, 'w') as f:
                f.write('left behind')
            left['files'].append(path)
        except OSError:
            pass
    return left
