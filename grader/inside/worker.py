"""Entry point of the student's worker process (runs inside the sandbox; never imported by the grader).

Started as `python -I -S -B worker.py '<config JSON>'`: isolated mode, no site hooks (so no
sitecustomize or .pth file from anywhere runs), no bytecode writes. The bootstrap, before any student code:
drops to the dedicated uid (when started as root), applies the rlimits and a seccomp filter against
network sockets, sets sys.path to the interpreter's
standard library plus the paths the grader names (first the worker's library, grader.sandbox.exposed: the
only simiam and grader it can import), imports the trusted modules, then answers requests on the private
pipe pair. Student output goes to fds 1 and 2, which the grader captures separately with a cap.
A third private pipe receives faulthandler's stack dump when the grader signals a timed-out call (SIGUSR1).

Ops: "ping"; "load" -> {"modules", "errors"}; "probe" (a function of the probes module, by allow-listed
name, called as fn(submission, **args)); "brain_start" (settings); "brain_step" (readings) -> command.
Every failure of student code (any BaseException, including SystemExit) becomes
{"ok": false, "error": {"type", "message", "file", "line"}}; os._exit or a kill ends the process and the
grader sees WorkerDied.
"""

import json
import os
import sys


def _drop_privileges(uid: int, gid: int) -> None:
    """Become `uid` for good (real, effective, saved); verify no capability is left."""
    os.setgroups([])
    os.setresgid(gid, gid, gid)
    os.setresuid(uid, uid, uid)
    if os.getresuid() != (uid, uid, uid) or os.getresgid() != (gid, gid, gid):
        raise SystemExit("sandbox: could not drop privileges")
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(("CapPrm:", "CapEff:")) and int(line.split()[1], 16) != 0:
                raise SystemExit("sandbox: capabilities left after dropping privileges")


# The trusted modules every worker needs, imported before the privilege drop and before student code.
_PRELOAD = ("math", "faulthandler", "resource", "numpy", "simiam.control", "simiam.course.weeks",
            "simiam.course.loader", "grader.inside.rlimits", "grader.inside.seccomp",
            "grader.inside.worker_loop", "ctypes")
# Standard-library modules a student may import, preloaded only when the dedicated uid cannot read the
# Python environment (subprocess mode, interpreter under a private home directory).
_STDLIB = ("cmath", "random", "statistics", "functools", "itertools", "collections", "copy", "time", "json",
           "dataclasses", "typing", "enum", "abc", "numbers", "operator", "re", "warnings", "traceback",
           "inspect", "signal", "socket", "select", "subprocess", "threading", "struct", "io", "string",
           "textwrap", "heapq", "bisect", "decimal", "fractions", "datetime", "array", "queue", "contextlib",
           "encodings.idna", "difflib")  # difflib: the supervisor's "did you mean", imported when needed


def _die_with_parent(parent: int | None) -> None:
    """SIGKILL this worker if the process that started it dies (set after the uid change, which clears it)."""
    import ctypes
    import signal

    try:
        ctypes.CDLL(None).prctl(1, int(signal.SIGKILL), 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError, TypeError):  # not Linux (Windows: no C library by name None)
        return
    if parent is not None and os.getppid() != parent:
        os._exit(70)  # the parent is already gone


def _bootstrap(config: dict) -> None:
    # Interpreter stdlib (from -I -S) first, then only what the grader names: site-packages and the repo.
    sys.path[:] = [p for p in sys.path if p] + list(config["paths"])
    import importlib

    stdlib = _STDLIB if config.get("preload_stdlib") else ()
    loader = config.get("loader", "").split(":")[0]
    for name in (*_PRELOAD, *stdlib, config.get("probes", "grader.inside.probes"), loader):
        try:
            importlib.import_module(name)
        except ImportError:
            pass  # a missing optional module shows up later as a clear error
    from grader.inside.worker_loop import numerics_report

    config["numerics"] = numerics_report()  # before the uid drop and before student code
    if config.get("uid") is not None:
        _drop_privileges(int(config["uid"]), int(config["gid"]))
    _die_with_parent(config.get("parent"))
    from grader.inside.rlimits import apply_rlimits
    from grader.inside.seccomp import install

    refused = apply_rlimits(config["rlimits"])
    if config["rlimits"] is not None and refused is None:
        raise SystemExit("sandbox: the resource limits could not be applied")  # never run unlimited silently
    config["refused_limits"] = refused or []  # reported in the ready message, before any student code
    config["seccomp"] = install()  # no network sockets, even where bubblewrap is missing
    os.environ.clear()
    home = config.get("private") or "/tmp"   # a plain subprocess's own folder (grader.sandbox.workdir)
    os.environ.update({"PATH": "/usr/bin:/bin", "HOME": home, "LANG": "C.UTF-8",
                       "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"})
    if config.get("private"):
        os.environ["TMPDIR"] = home
        if "tempfile" in sys.modules:   # it may have picked its folder already
            vars(sys.modules["tempfile"])["tempdir"] = None


def _stdio_channel(config: dict) -> None:
    """The portable channel (grader.sandbox.channel): requests on stdin, answers on stdout. Both move to
    private descriptors that no child process inherits; fd 0 becomes empty and fd 1 joins fd 2, the
    captured output, so whatever the student prints can never pass for an answer's framing. The stack
    dump's pipe, where the system has SIGUSR1, is passed as its own descriptor (config["fd_dump"])."""
    fd_in, fd_out = os.dup(0), os.dup(1)
    for fd in (fd_in, fd_out):
        _binary(fd)
    null = os.open(os.devnull, os.O_RDONLY)
    os.dup2(null, 0)
    os.close(null)
    os.dup2(2, 1)
    config.update(fd_in=fd_in, fd_out=fd_out)


def _binary(fd: int) -> None:
    """Windows opens standard descriptors in text mode (\n -> \r\n): JSON lines need bytes as written."""
    if sys.platform == "win32":  # mypy knows msvcrt and O_BINARY there only
        import msvcrt

        msvcrt.setmode(fd, os.O_BINARY)


def main() -> None:
    config = json.loads(sys.argv[1])
    del sys.argv[1:]  # nothing secret is passed, but student code has no use for it either
    if config.get("channel") == "stdio":
        _stdio_channel(config)
    _bootstrap(config)
    from grader.inside.worker_loop import serve

    serve(config)


if __name__ == "__main__":
    main()
