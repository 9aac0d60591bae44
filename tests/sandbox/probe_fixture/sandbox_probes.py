"""Probes for the sandbox tests (run inside the worker, like grader/inside/probes.py).

`attack(sub, fn="attack", ...)` calls `fn(**args)` in the submission's differential_drive.py;
`uni_to_diff` calls the student's function with a stand-in robot.
"""

from types import SimpleNamespace

__all__ = ["attack", "uni_to_diff", "echo", "length", "nap", "modules"]


def _robot() -> SimpleNamespace:
    return SimpleNamespace(wheel_radius=0.0325, wheel_base_length=0.09925, max_vel=80.0, min_vel=0.0)


def uni_to_diff(sub, v: float, w: float):
    return sub.module("differential_drive").uni_to_diff(_robot(), v, w)


def attack(sub, fn: str = "attack", **args):
    return getattr(sub.module("differential_drive"), fn)(**args)


def echo(sub, value=None):
    return value


def length(sub, value=""):
    """The length of what it was sent: a large request with a small answer."""
    return len(value)


def nap(sub, seconds: float = 0.0):
    """Sleep `seconds`, then answer them: a slow but honest probe."""
    import time

    time.sleep(seconds)
    return seconds


def modules(sub, extra=()):
    """The names of the modules the worker holds after its start, the load and importing `extra`."""
    import importlib
    import sys

    for name in extra:
        importlib.import_module(name)
    return sorted(sys.modules)


def not_allowed(sub):  # public but not in __all__: the worker must refuse it
    return "should never run"
