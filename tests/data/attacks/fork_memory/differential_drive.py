"""Attack (issue 10.8): the memory limit binds each process, so fork children that each take most of it."""
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


def attack(children=3, mb=200, **args):
    """Bytes held at once by this process and its children (each child reports after allocating)."""
    held = [bytearray(mb * 2**20)]  # the worker itself keeps one share
    read, write = os.pipe()
    forked = []
    error = ''
    for _ in range(children):
        try:
            pid = os.fork()
        except OSError as exc:
            error = f'{type(exc).__name__}: {exc}'
            break
        if pid == 0:
            try:
                held.clear()  # the child's address space starts as a copy of the parent's: give that back
                mine = bytearray(mb * 2**20)
                os.write(write, b'1')
                time.sleep(60)  # hold it while the parent counts (the grader kills the tree at the end)
                del mine
            finally:
                os._exit(0)
        forked.append(pid)
    os.close(write)
    reported = 0
    for _ in forked:
        reported += len(os.read(read, 1))
    return {'bytes_held': (len(held) + reported) * mb * 2**20, 'error': error}
