"""Attack: return objects that lie (__eq__, __float__, __bool__), NaN, infinities, huge numbers."""
import math


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


class Liar:
    def __eq__(self, other):
        return True

    def __float__(self):
        return 1.0

    def __bool__(self):
        return True

    __hash__ = object.__hash__


class LyingFloat(float):
    def __eq__(self, other):
        return True


def attack(kind='eq', **args):
    if kind == 'eq':
        return Liar(), Liar()
    if kind == 'float_subclass':
        return LyingFloat(1.0), LyingFloat(2.0)
    if kind == 'nan':
        return math.nan, math.nan
    if kind == 'inf':
        return math.inf, -math.inf
    if kind == 'huge_int':
        return 10 ** 400, 1
    if kind == 'huge_float':
        return 1e308, -1e308
    if kind == 'deep':
        value = []
        for _ in range(10000):
            value = [value]
        return value
    if kind == 'big_string':
        return 'x' * (10 * 2 ** 20)
    raise ValueError(kind)
