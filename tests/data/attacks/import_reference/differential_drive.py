"""Attack (issue 10.7): get full marks by calling the package's reference code instead of writing it:
import it by name, read its file, or reach it through an installed copy of the package."""
import importlib
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


def attack(modules=(), paths=(), **args):
    """{"imported": [modules that imported], "read": [paths that could be read], "path": sys.path}."""
    imported, read = [], []
    for name in modules:
        try:
            importlib.import_module(name)
            imported.append(name)
        except Exception:  # noqa: BLE001 - ImportError, or whatever the module raises at import
            pass
    for path in paths:
        try:
            with open(path, 'rb') as f:
                f.read(10)
            read.append(path)
        except OSError:
            pass
    listed = {}
    for folder in sys.path:
        for name in ('simiam', 'grader', 'instructor_tools'):
            here = os.path.join(folder, name)
            if os.path.isdir(here):
                listed[here] = sorted(os.listdir(here))
    return {'imported': imported, 'read': read, 'listed': listed}
