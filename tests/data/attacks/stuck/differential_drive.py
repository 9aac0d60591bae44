"""Attack (not really): code stuck in a method, spinning or sleeping; the timeout must name the line."""
import signal
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


class Spinner:
    def spin(self):
        while True: pass  # noqa: E701 - STUCK: spin

    def doze(self):
        time.sleep(60)  # STUCK: doze

    def late(self, seconds=1.0):
        # A worker that takes the stack-dump signal late, as one waiting for the CPU on a loaded machine
        # does: the signal stays pending while blocked, and is taken at the unblock. Seconds of CPU time,
        # the clock the call's limit is judged on (grader.sandbox.worker_clock).
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGUSR1})
        end = time.process_time() + seconds
        while time.process_time() < end:
            pass
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGUSR1})  # STUCK: late
        while True: pass  # noqa: E701


def attack(how="spin", **args):
    return getattr(Spinner(), how)(**args)
