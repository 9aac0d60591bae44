"""Run under no_posix.py (tests/sandbox/test_windows_like.py): what of POSIX Python code still sees."""
import os
import platform  # noqa: F401 - patched by the emulation
import select
import signal
import sys

from grader.inside.seccomp import available

modules = [n for n in ("fcntl", "resource", "termios", "pwd") if sys.modules.get(n, 0) is not None]
attrs = [n for n, m in (("poll", select), ("epoll", select), ("setsid", os), ("killpg", os), ("fork", os),
                        ("geteuid", os), ("set_blocking", os), ("O_NOFOLLOW", os), ("SIGUSR1", signal),
                        ("SIGXCPU", signal), ("setitimer", signal))
         if hasattr(m, n)]
try:
    open("/proc/self/status").close()
    proc = "readable"
except FileNotFoundError:
    proc = "gone"
print(modules, attrs, proc, available())
