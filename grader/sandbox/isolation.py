"""How the worker is isolated: bubblewrap when it works here, else a plain subprocess; and which uid it gets.

`bwrap` mode: own PID, network, IPC and UTS namespaces; a root made of read-only binds of /usr, the Python
environment, the worker's library (grader.sandbox.exposed: the student-facing framework and the worker's own
code) at /library, the spliced submission at /submission, with any installed simiam/ or grader/ folder
hidden behind an empty one; a private size-capped /tmp; minimal /proc and /dev; all capabilities dropped.
`subprocess` mode: a separate process in its own session with the same rlimits, the same clean
environment and the same seccomp filter (no network sockets), but it sees the file system as its uid does.

As root, the worker drops to a dedicated uid picked per session, so RLIMIT_NPROC binds and every process the
student starts (even after setsid or a double fork) can be killed by uid. Both modes also make the worker
die with the grading process (bubblewrap's --die-with-parent; PR_SET_PDEATHSIG in the worker). Both are
tied to the *thread* that started the worker: start and use a session from one long-lived thread.
"""

from __future__ import annotations

import functools
import json
import os
import random
import shutil
import site
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

from grader.sandbox import reach
from grader.sandbox.capabilities import is_root
from grader.sandbox.exposed import WORKER, build_library, installed_copies
from grader.sandbox.library import shared_library
from grader.sandbox.workdir import PRIVATE
from simiam import numerics
from simiam.course.folders import CHECKOUT

BWRAP = "bwrap"
SUBPROCESS = "subprocess"
_UID_RANGE = (200_000, 260_000)

NOTES = {
    BWRAP: "bubblewrap sandbox: no network, private /tmp, own PID namespace, read-only view of only the "
           "spliced submission, the Python environment and the course's student-facing modules (no "
           "reference code), an unprivileged uid and a seccomp filter; limits on time, memory, processes, "
           "files and output.",
    SUBPROCESS: "no bubblewrap: student code runs in a separate{limited} process{uid}{net}; it is "
                "killed with its whole process tree, and only JSON crosses back; it can import only the "
                "course's student-facing modules, but it can read what its user can read{reads} and "
                "write to /tmp while it runs. {leftovers}",
}


@dataclass
class WorkerPlan:
    """Everything needed to start one worker: argv, environment, and what the kill has to cover."""

    mode: str
    argv: list[str]
    env: dict[str, str]
    uid: int | None           # dedicated uid the worker drops to (None: runs as the grader's user)
    note: str
    cwd: str
    config: dict = field(default_factory=dict)


LIBRARY = "/library"  # where bubblewrap binds the worker's library (grader.sandbox.exposed)


def python_paths() -> list[str]:
    """The third-party sys.path entries the worker needs (site-packages: numpy). simiam and grader come
    from the worker's library instead (grader.sandbox.exposed), never from here."""
    paths = [p for p in site.getsitepackages() if os.path.isdir(p)]
    # what this interpreter really uses (getsitepackages can miss a layout, e.g. PYTHONPATH installs)
    paths += [p for p in sys.path if p.endswith(("site-packages", "dist-packages")) and os.path.isdir(p)
              and p not in paths]
    return paths


def trusted_binds(probes_file: Path | None) -> list[str]:
    """Files and folders the worker may read, besides /usr, the library and the submission (bwrap mode)."""
    binds = {sys.prefix, sys.base_prefix, str(Path(sys.executable).resolve().parent.parent)}
    binds.update(p for p in python_paths() if "-packages" in p)
    if probes_file is not None:
        binds.add(str(probes_file))
    return _outermost(sorted(binds))


def _hide(folders: list[str]) -> list[str]:
    """An empty, read-only, tiny tmpfs over each folder (bwrap applies mounts in order: after the binds)."""
    args: list[str] = []
    for folder in folders:
        args += ["--perms", "0555", "--size", "4096", "--tmpfs", folder, "--remount-ro", folder]
    return args


def _outermost(paths: list[str]) -> list[str]:
    """Drop paths already inside another bound path, or under /usr (bound as a whole)."""
    out: list[str] = []
    for p in sorted(paths, key=len):
        if p.startswith("/usr/") or any(p == q or p.startswith(q.rstrip("/") + "/") for q in out):
            continue
        out.append(p)
    return out


@functools.lru_cache(maxsize=1)
def bwrap_path() -> str | None:
    return shutil.which("bwrap")


@functools.lru_cache(maxsize=1)
def bwrap_works() -> tuple[bool, str]:
    """Try a minimal sandbox once (namespaces may be forbidden even where the binary exists)."""
    exe = bwrap_path()
    if exe is None:
        return False, "bubblewrap (bwrap) is not installed"
    prefix = str(Path(sys.executable).resolve().parent.parent)
    argv = [exe, *_bwrap_base(is_root(), 1 << 20), *_bind_args([sys.prefix, prefix]),
            "--", sys.executable, "-I", "-S", "-c", "pass"]
    try:
        done = subprocess.run(argv, capture_output=True, timeout=10)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return False, f"bubblewrap failed to start: {exc}"
    if done.returncode != 0:
        why = done.stderr.decode(errors="replace")[:300].strip()
        return False, f"bubblewrap cannot create a sandbox here: {why}"
    return True, ""


def _bwrap_base(as_root: bool, tmp_bytes: int, drop_uid: bool = False) -> list[str]:
    args = ["--die-with-parent", "--new-session", "--unshare-pid", "--unshare-net", "--unshare-ipc",
            "--unshare-uts", "--unshare-cgroup-try", "--hostname", "sandbox", "--cap-drop", "ALL"]
    if not as_root:
        args += ["--unshare-user"]
    elif drop_uid:
        # Only to drop to the dedicated uid in the worker's bootstrap; gone after the drop.
        args += ["--cap-add", "CAP_SETUID", "--cap-add", "CAP_SETGID"]
    args += ["--ro-bind", "/usr", "/usr"]
    for top in ("/bin", "/sbin", "/lib", "/lib64", "/lib32"):
        if os.path.islink(top):
            args += ["--symlink", os.readlink(top), top]
        elif os.path.isdir(top):
            args += ["--ro-bind", top, top]
    args += ["--ro-bind-try", "/etc/ld.so.cache", "/etc/ld.so.cache",
             "--proc", "/proc", "--dev", "/dev", "--remount-ro", "/dev",
             "--size", str(tmp_bytes), "--perms", "1777", "--tmpfs", "/tmp"]
    return args


def _bind_args(paths: list[str]) -> list[str]:
    """Read-only binds of `paths` at the same place, creating their ancestors world-traversable."""
    made: set[str] = set()
    args: list[str] = []
    for path in _outermost(paths):
        args += _mkdirs(path, made) + ["--ro-bind", path, path]
    return args


def _mkdirs(path: str, made: set[str]) -> list[str]:
    """--dir for each missing ancestor, world-traversable (bwrap would make them 0700)."""
    args: list[str] = []
    parts = Path(path).parts[1:-1]
    current = ""
    for part in parts:
        current += "/" + part
        if current in made or current in ("/usr", "/tmp", "/proc", "/dev"):
            continue
        made.add(current)
        args += ["--perms", "0755", "--dir", current]
    return args


def pick_uid() -> int | None:
    """A uid no process uses now, so that killing by uid can only hit this session's processes
    (None when the grader is not root and cannot switch uid, or no spare uid is mapped here)."""
    if not is_root() or not os.path.isdir("/proc"):
        return None
    low, high = _uid_range()
    if high - low < 1000:
        return None
    used = set()
    for entry in os.scandir("/proc"):
        if entry.name.isdigit():
            try:
                used.add(entry.stat().st_uid)
            except OSError:
                pass
    while True:
        uid = random.randrange(low, high)
        if uid not in used:
            return uid


def _mapped(path: str) -> list[tuple[int, int]]:
    """[start, end) id ranges usable in this user namespace (from /proc/self/uid_map or gid_map)."""
    try:
        with open(path) as f:
            return [(int(a), int(a) + int(n)) for a, _b, n in (line.split() for line in f if line.strip())]
    except (OSError, ValueError):
        return [(0, 65536)]


def _uid_range() -> tuple[int, int]:
    """_UID_RANGE if it is mapped for both uids and gids, else the largest mapped range above 1000
    (rootless containers often map only 65536 ids)."""
    ranges = [(max(a, c), min(b, d)) for a, b in _mapped("/proc/self/uid_map")
              for c, d in _mapped("/proc/self/gid_map") if min(b, d) > max(a, c)]
    if any(a <= _UID_RANGE[0] and _UID_RANGE[1] <= b for a, b in ranges):
        return _UID_RANGE
    spans = [(max(a, 1000), min(b, 65534)) for a, b in ranges]
    return max(spans, key=lambda r: r[1] - r[0], default=(0, 0))


@functools.lru_cache(maxsize=1)
def _private_env() -> bool:
    """True if a uid without privileges cannot read the interpreter, its standard library or its packages
    (grader.sandbox.reach: a virtual environment or pyenv under a folder only its owner can open)."""
    paths = [sys.executable, os.path.dirname(os.__file__), *python_paths()]
    return not all(reach.readable(p) for p in paths if os.path.exists(p))


def course_files() -> dict[str, Path]:
    """What the subprocess note says the worker can or cannot read, by the name it gives them: the grader's
    own files (its checks' maths) and, in the course checkout, the reference solutions."""
    files = {"the grader's files": Path(__file__).resolve().parents[1] / "reference.py"}
    if (CHECKOUT / "solutions").is_dir():
        files["solutions/"] = CHECKOUT / "solutions"
    return files


def _what_it_reads(own_uid: bool) -> str:
    """The files of `course_files` the worker can read, as the note's parenthesis: all of them under the
    grader's user or root; under a dedicated uid only those every user can reach (grader.sandbox.reach), so
    the note is true of the machine it runs on, a checkout in a private folder included."""
    files = course_files()
    inside = [name for name, path in files.items() if not own_uid or reach.readable(path)]
    outside = [name for name in files if name not in inside]
    parts = [f"{' and '.join(inside)} included"] if inside else []
    if outside:
        parts.append(f"not {' or '.join(outside)}, which only their owner can reach here")
    return f" ({'; '.join(parts)})"


def clean_env() -> dict[str, str]:
    """The worker's whole environment: nothing inherited from the grader (no tokens, no paths) but the
    numeric environment simiam.numerics pins before the worker's numpy loads (one BLAS kernel, one thread,
    one SIMD level: the same wheel speeds from the same code on every CPU)."""
    env = {"PATH": "/usr/bin:/bin", "HOME": "/tmp", "LANG": "C.UTF-8", **numerics.plan()}
    if os.name == "nt":  # Windows' runtime needs its own folders to start Python, and a temp folder
        env.update({k: os.environ[k] for k in WINDOWS_ENV if k in os.environ})
    return env


WINDOWS_ENV = ("SYSTEMROOT", "WINDIR", "TEMP", "TMP")  # folders of the system, not the user's secrets


def worker_library(mode: str, beside: Path) -> Path:
    """The folder of the only simiam and grader a worker in `mode` can import (grader.sandbox.exposed).
    bubblewrap binds it read-only, so every bubblewrap worker shares one, with its bytecode, built once
    (grader.sandbox.library); a plain subprocess may run as a user who can write to it, so it gets a
    fresh copy at `beside` (removed with the session's files)."""
    if mode == BWRAP:
        return shared_library()
    return build_library(beside)


def plan_worker(mode: str, submission: Path, config: dict, *, tmp_bytes: int, library: Path,
                uid: int | None = None, extra_paths: tuple[str, ...] = (),
                probes_file: Path | None = None) -> WorkerPlan:
    """Build the argv for one worker in `mode` ("bwrap" or "subprocess"). `config` is the worker's config;
    `library` the folder built by grader.sandbox.exposed.build_library (the only simiam and grader the
    worker can import); `uid` the dedicated uid (and gid) to drop to, when the grader runs as root."""
    as_root = is_root()
    python = [sys.executable, "-I", "-S", "-B"]
    env = clean_env()
    if mode == BWRAP:
        uid = uid if as_root else None
        config = dict(config, paths=[LIBRARY, *python_paths(), *extra_paths])
        config.update(submission="/submission", uid=uid, gid=uid)
        binds = trusted_binds(probes_file) + list(extra_paths)
        args = [bwrap_path() or "bwrap", *_bwrap_base(as_root, tmp_bytes, drop_uid=uid is not None),
                *_bind_args(binds), *_hide(installed_copies(python_paths()))]
        args += ["--ro-bind", str(library), LIBRARY, "--ro-bind", str(submission), "/submission",
                 "--chdir", "/submission", "--clearenv"]
        for key, value in env.items():
            args += ["--setenv", key, value]
        argv = args + ["--", *python, f"{LIBRARY}/{WORKER}", json.dumps(config)]
        return WorkerPlan(BWRAP, argv, env, uid, NOTES[BWRAP], "/", config)
    uid = uid if as_root else None
    preload = uid is not None and _private_env()
    config = dict(config, paths=[str(library), *python_paths(), *extra_paths])
    config.update(submission=str(submission), uid=uid, gid=uid, preload_stdlib=preload, parent=os.getpid())
    private = submission.parent / PRIVATE      # the worker's own HOME and TMPDIR (grader.sandbox.workdir)
    if uid is not None and private.is_dir():
        config["private"] = str(private)
    argv = [*python, str(library / WORKER), json.dumps(config)]
    return WorkerPlan(SUBPROCESS, argv, env, uid, describe(SUBPROCESS), str(submission), config)


def describe(mode: str, official: bool = False) -> str:
    """One or two sentences on what holds in `mode` on this machine, for the result and the report; it
    starts "local check only: ..." when the system lacks part of the sandbox (capabilities.missing), or
    capabilities.OFFICIAL_PARTIAL when that system is a platform's official grading."""
    if mode == BWRAP:
        return NOTES[BWRAP]
    from grader.sandbox.capabilities import local_only_note, missing, official_note

    items = missing(*bwrap_works(), official=official)
    details = _describe_subprocess(official)
    if not items:
        return details
    first = official_note(items) if official else local_only_note(items)
    return f"{first} In detail: {details[0].lower()}{details[1:]}"


def _describe_subprocess(official: bool = False) -> str:
    from grader.inside.seccomp import available
    from grader.sandbox.capabilities import has_module

    limited = ", resource-limited" if has_module("resource") else ""
    note = functools.partial(NOTES[SUBPROCESS].format, limited=limited)
    net = " with network sockets blocked by a seccomp filter" if available() else " with network access"
    cannot = ("Files it writes anywhere its user can write and the System V / POSIX IPC objects it "
              "creates outlive the grading: nothing tells them apart from yours, so none are removed.")
    if not is_root():
        if official:  # a platform that runs its grader as a user without privileges: nothing to drop to
            return note(net=net, uid=" under the grader's own user (not root here, so no uid to drop to): it "
                        "could signal the grader and write where the grader can", reads=_what_it_reads(False),
                        leftovers=cannot)
        return note(net=net, uid=" under your own user, so it could also signal the grader, write where you "
                    "can write and leave processes behind: treat this result as advisory",
                    reads=_what_it_reads(own_uid=False), leftovers=cannot)
    if _uid_range()[1] - _uid_range()[0] < 1000:
        return note(net=net, uid=" that stays root (no spare uid is mapped here, so the process limit does "
                    "not bind and files root can write are writable)", reads=_what_it_reads(own_uid=False),
                    leftovers=cannot)
    env_note = " (the Python environment is private to root here, so only modules preloaded before the " \
               "drop can be imported)" if _private_env() else ""
    swept = ("It has a private HOME and TMPDIR of its own; what its uid leaves in any folder of this machine "
             "that uid can write (found by walking the writable mounts), and its System V IPC objects, are "
             "removed when its grading ends or is killed.")
    return note(net=net, uid=f" under its own unprivileged uid{env_note}", reads=_what_it_reads(own_uid=True),
                leftovers=swept)
