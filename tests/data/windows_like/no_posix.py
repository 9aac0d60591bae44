"""Make this interpreter look like Windows to Python code, then run the grader or a worker in it.

Emulation for tests/sandbox/test_windows_like.py (no Windows machine is available): before anything else
is imported, every POSIX-only piece the grader or the worker could reach is made unavailable:

- modules Windows lacks: fcntl, resource, termios, pwd, grp, pty, tty (set to None in sys.modules);
- select.poll and select.epoll (Windows has only select() on sockets), so selectors and subprocess pick
  what they would pick there;
- os: fork, setsid, killpg, process groups, uids and gids, chown, sched_getaffinity, getloadavg,
  set_blocking (Python 3.11 on Windows has none for pipes), O_NOFOLLOW and O_DIRECTORY, dir_fd support;
- signals Windows lacks (SIGUSR1, SIGXCPU, SIGALRM, setitimer, pthread_sigmask...). SIGKILL stays: the
  standard library's POSIX subprocess.Popen.kill needs it here (on Windows, kill is TerminateProcess);
- /proc: open, os.open, os.stat, os.scandir and os.listdir raise FileNotFoundError for it (Python code
  only: C libraries such as OpenBLAS still read it);
- text files opened without an encoding are read and written as cp1252, Windows' usual ANSI code page;
- platform.machine() says "AMD64", as on Windows, so no seccomp filter is offered; ctypes.CDLL(None)
  raises, as there is no C library by that name on Windows.

sys.platform and os.name stay Linux's (numpy and the standard library branch on them): the emulation is
of missing capabilities, which is what the grader's code tests for.

    python no_posix.py run LAUNCHER MODULE:FUNCTION ARGS...   a console script (grader.cli:main is `grade`),
                                                               its workers started through LAUNCHER
    python no_posix.py worker [-I -S -B] SCRIPT ARGS...   a worker (what LAUNCHER runs)
"""

import builtins
import io
import os
import select
import signal
import sys

assert "selectors" not in sys.modules and "subprocess" not in sys.modules, "no_posix must run first"

for name in ("fcntl", "resource", "termios", "pwd", "grp", "pty", "tty"):
    sys.modules[name] = None  # type: ignore[assignment]  # an import of it raises ImportError

for name in ("poll", "epoll", "devpoll", "kqueue"):
    if hasattr(select, name):
        delattr(select, name)

for name in ("fork", "forkpty", "setsid", "getsid", "killpg", "getpgid", "setpgid", "getpgrp", "setpgrp",
             "getuid", "geteuid", "getgid", "getegid", "getresuid", "getresgid", "setresuid", "setresgid",
             "setuid", "setgid", "seteuid", "setegid", "setgroups", "getgroups", "initgroups", "chown",
             "lchown", "fchown", "sched_getaffinity", "sched_setaffinity", "getloadavg", "wait3", "wait4",
             "set_blocking", "get_blocking"):  # Windows pipes cannot be non-blocking before Python 3.12
    if hasattr(os, name):
        delattr(os, name)

for name in ("O_NOFOLLOW", "O_DIRECTORY", "O_CLOEXEC", "O_NOCTTY", "O_NONBLOCK"):  # no such open flags
    if hasattr(os, name):
        delattr(os, name)
os.supports_dir_fd = set()  # no *at() calls on Windows: simiam.safe_write takes its by-path way

WINDOWS_SIGNALS = {"SIGABRT", "SIGFPE", "SIGILL", "SIGINT", "SIGSEGV", "SIGTERM", "SIGBREAK",
                   "SIGKILL"}  # SIGKILL: see the docstring
for name in dir(signal):
    if name.startswith("SIG") and not name.startswith(("SIG_", "SIGRT")) and name not in WINDOWS_SIGNALS:
        delattr(signal, name)
for name in ("alarm", "setitimer", "getitimer", "pause", "pthread_kill", "pthread_sigmask", "sigpending",
             "sigwait", "siginterrupt", "ITIMER_REAL", "ITIMER_VIRTUAL", "ITIMER_PROF"):
    if hasattr(signal, name):
        delattr(signal, name)


def _no_proc(function):
    def refuse(path, *args, **kwargs):
        name = os.fsdecode(path) if isinstance(path, (str, bytes, os.PathLike)) else ""
        if name == "/proc" or name.startswith("/proc/"):
            raise FileNotFoundError(2, "No such file or directory (no /proc on Windows)", name)
        return function(path, *args, **kwargs)
    return refuse


def _windows_encoding(function):
    """Text files opened without an encoding use the ANSI code page on Windows (cp1252 in Western
    Europe and the Americas), not UTF-8: so here too (the C locale of this machine would say UTF-8)."""
    def opened(file, mode="r", buffering=-1, encoding=None, *args, **kwargs):
        if "b" not in mode and encoding in (None, "locale"):
            encoding = "cp1252"
        return function(file, mode, buffering, encoding, *args, **kwargs)
    return opened


builtins.open = io.open = _no_proc(_windows_encoding(io.open))
for name in ("open", "stat", "lstat", "scandir", "listdir"):
    setattr(os, name, _no_proc(getattr(os, name)))

import ctypes  # noqa: E402
import platform  # noqa: E402

platform.machine = lambda: "AMD64"
_CDLL = ctypes.CDLL


class _WindowsCDLL(_CDLL):
    def __init__(self, name, *args, **kwargs):
        if name is None:
            raise OSError("no C library by the name None on Windows")
        super().__init__(name, *args, **kwargs)


ctypes.CDLL = _WindowsCDLL


def main(argv: list[str]) -> None:
    role, rest = argv[0], argv[1:]
    if role == "run":
        sys.executable = rest[0]  # workers start through the launcher, so they run in this emulation too
        import importlib

        module, _, function = rest[1].partition(":")
        sys.exit(getattr(importlib.import_module(module), function)(rest[2:]))
    while rest and rest[0].startswith("-"):  # the interpreter flags the launcher passed on (-I -S -B)
        rest.pop(0)
    import runpy

    sys.argv = rest
    sys.path[0] = os.path.dirname(os.path.abspath(rest[0]))
    runpy.run_path(rest[0], run_name="__main__")


if __name__ == "__main__":
    main(sys.argv[1:])
