"""Attack: leave a note for a student graded later in every folder this uid can write (issue 30 item 3):
not only /tmp and its like but /run/lock and any other folder open to all, found by looking, and TMPDIR and
HOME; then, graded as another student, look for the notes."""

import os


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


def _folders():
    """Where to try: the usual places, the environment's, and every folder open to all found in a walk
    of the places a shared folder usually sits."""
    seen = ['/run/lock', '/var/lock', '/tmp', '/var/tmp', '/dev/shm', '/dev/mqueue',
            os.environ.get('TMPDIR', ''), os.environ.get('HOME', '')]
    for top in ('/run', '/var', '/dev', '/tmp'):
        for folder, subfolders, _files in os.walk(top):
            if folder.count('/') > 4:
                subfolders[:] = []
            if os.access(folder, os.W_OK | os.X_OK):
                seen.append(folder)
    return [f for i, f in enumerate(seen) if f and f not in seen[:i]]


def read(paths=(), **args):
    """What of `paths` this student can read."""
    found = {}
    for path in paths:
        try:
            with open(path) as f:
                found[path] = f.read()
        except OSError:
            pass
    return found


def leave(tag='simiam-note', **args):
    """A note in every folder this uid can write; the paths written."""
    left = []
    for folder in _folders():
        path = os.path.join(folder, f'{tag}-{os.getpid()}')
        try:
            with open(path, 'w') as f:
                f.write('the hidden goal is (1.2, 0.4)')
            os.chmod(path, 0o644)
            left.append(path)
        except OSError:
            pass
    return left
