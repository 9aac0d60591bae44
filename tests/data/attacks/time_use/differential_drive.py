"""Attack (and honest work): ways of using time that the per-call limit must see, whatever the machine does."""
import os
import signal
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


def _spin():
    while True:
        pass


def work(seconds=1.0):
    """Honest but slow: `seconds` of CPU time, then the answer."""
    end = time.process_time() + seconds
    while time.process_time() < end:
        pass
    return seconds


def threads(n=4):
    """CPU burnt in threads while the main thread waits: every thread's CPU counts."""
    for _ in range(n):
        threading.Thread(target=_spin, daemon=True).start()
    threading.Event().wait()


def fork():
    """CPU burnt in a child while the parent waits for it (plain subprocess mode; the sandbox forbids fork)."""
    pid = os.fork()
    if pid == 0:
        _spin()
    os.waitpid(pid, 0)


def self_stop():
    """The worker stops itself: to the grader it looks like a machine that paused it."""
    os.kill(os.getpid(), signal.SIGSTOP)
    return "went on"


def attack(how="work", **args):
    return globals()[how](**args)
