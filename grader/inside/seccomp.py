"""A small seccomp filter the worker installs on itself: no network, no new processes, no new namespaces.

bubblewrap already gives the worker an empty network namespace; without bubblewrap this filter is what
keeps student code off the network. It allows every system call except:
- socket() for any family but AF_UNIX (EACCES);
- new processes: fork(), vfork() and clone() without CLONE_THREAD (EACCES). Threads still start. This is
  what makes the memory limit one per submission: RLIMIT_AS binds each process, and a worker that cannot
  fork is one process (no writable cgroup v2 memory controller is needed for that). Student code has no
  use for processes; `os.fork`, `subprocess` and `multiprocessing` raise PermissionError;
- clone() with a CLONE_NEW* flag, unshare(), setns() (no user namespace in which to play root);
- sending a stop signal (SIGSTOP, SIGTSTP, SIGTTIN, SIGTTOU) by any of kill, tkill, tgkill, rt_sigqueueinfo,
  rt_tgsigqueueinfo, pidfd_send_signal (EPERM): a stopped worker looks to the grader like a machine that
  paused it, which is never charged to the student (grader.sandbox.worker_clock), so the worker may not
  stop itself;
- clone3() (ENOSYS, so the C library falls back to clone(), whose flags the filter can see);
- io_uring_setup (it could open sockets behind the filter's back), bpf, perf_event_open, userfaultfd,
  keyctl/add_key/request_key;
- any call through a foreign ABI (x32, or 32-bit int 0x80 on x86-64, which would reach socketcall).
Only x86-64 and aarch64 are known; elsewhere nothing is installed and `install()` returns False.
"""

from __future__ import annotations

import ctypes
import errno
import platform
import struct
import sys

_PR_SET_NO_NEW_PRIVS = 38
_PR_SET_SECCOMP = 22
_SECCOMP_MODE_FILTER = 2
_RET_ALLOW = 0x7FFF0000
_RET_ERRNO = 0x00050000
_AF_UNIX = 1
_CLONE_NEW_ANY = 0x7E020000  # NEWNS | NEWCGROUP | NEWUTS | NEWIPC | NEWUSER | NEWPID | NEWNET
_CLONE_THREAD = 0x00010000
DENY_NEW_PROCESSES = True  # False only in the tests' wrong version (tests/sandbox/test_fork_memory.py)

# per machine: AUDIT_ARCH, first foreign-ABI number (or None), and the system call numbers used
_ARCHES = {
    "x86_64": (0xC000003E, 0x40000000, {
        "fork": 57, "vfork": 58, "socket": 41, "clone": 56, "clone3": 435, "unshare": 272, "setns": 308,
        "io_uring_setup": 425, "bpf": 321, "perf_event_open": 298, "userfaultfd": 323, "keyctl": 250,
        "add_key": 248, "request_key": 249, "kill": 62, "tkill": 200, "tgkill": 234, "rt_sigqueueinfo": 129,
        "rt_tgsigqueueinfo": 297, "pidfd_send_signal": 424}),
    "aarch64": (0xC00000B7, None, {
        "socket": 198, "clone": 220, "clone3": 435, "unshare": 97, "setns": 268, "io_uring_setup": 425,
        "bpf": 280, "perf_event_open": 241, "userfaultfd": 282, "keyctl": 219, "add_key": 217,
        "request_key": 218, "kill": 129, "tkill": 130, "tgkill": 131, "rt_sigqueueinfo": 138,
        "rt_tgsigqueueinfo": 240, "pidfd_send_signal": 424}),
}
_FORKS = ("fork", "vfork")  # aarch64 has neither: its C library forks through clone()
_DENIED = ("unshare", "setns", "io_uring_setup", "bpf", "perf_event_open", "userfaultfd", "keyctl", "add_key",
           "request_key")
# the system calls that send a signal, by which argument holds the signal's number
_SIGNAL_AT = {"kill": 1, "tkill": 1, "rt_sigqueueinfo": 1, "pidfd_send_signal": 1, "tgkill": 2,
              "rt_tgsigqueueinfo": 2}
_STOP_SIGNALS = (19, 23)  # SIGSTOP, SIGTSTP, SIGTTIN, SIGTTOU: 19..22 on x86-64 and aarch64 alike

# classic BPF opcodes
_LD_W_ABS = 0x20
_JEQ_K = 0x15
_JGE_K = 0x35
_JSET_K = 0x45
_RET_K = 0x06


def program(machine: str | None = None) -> bytes | None:
    """The filter for `machine` (default: this one) as packed sock_filter entries, or None if unknown."""
    arch = _ARCHES.get(machine or platform.machine())
    if arch is None:
        return None
    audit_arch, foreign, nr = arch
    # (code, true-label, false-label, k); labels are resolved to relative jumps below
    code: list[tuple[int | str, str | None, str | None, int]] = [
        (_LD_W_ABS, None, None, 4),                      # A = arch
        (_JEQ_K, "native", "enosys", audit_arch),
        ("native", None, None, 0),
        (_LD_W_ABS, None, None, 0),                      # A = system call number
        (_JGE_K, "deny", None, foreign if foreign is not None else 0xFFFFFFFF),
        (_JEQ_K, "enosys", None, nr["clone3"]),
        *[(_JEQ_K, "deny", None, nr[name]) for name in _DENIED],
        *[(_JEQ_K, "deny", None, nr[name]) for name in _FORKS if name in nr and DENY_NEW_PROCESSES],
        (_JEQ_K, "socket", None, nr["socket"]),
        (_JEQ_K, "clone", None, nr["clone"]),
        *[(_JEQ_K, f"signal{at}", None, nr[name]) for name, at in _SIGNAL_AT.items()],
        (_RET_K, None, None, _RET_ALLOW),
        *[step for at in (1, 2) for step in (
            (f"signal{at}", None, None, 0),
            (_LD_W_ABS, None, None, 16 + 8 * at),        # A = low word of args[at]: the signal
            (_JGE_K, "allow", None, _STOP_SIGNALS[1]),
            (_JGE_K, "stop", "allow", _STOP_SIGNALS[0]))],
        ("stop", None, None, 0),
        (_RET_K, None, None, _RET_ERRNO | errno.EPERM),
        ("socket", None, None, 0),
        (_LD_W_ABS, None, None, 16),                     # A = low word of args[0]: the address family
        (_JEQ_K, "allow", "deny", _AF_UNIX),
        ("clone", None, None, 0),
        (_LD_W_ABS, None, None, 16),                     # A = low word of args[0]: the clone flags
        (_JSET_K, "deny", "thread" if DENY_NEW_PROCESSES else "allow", _CLONE_NEW_ANY),
        ("thread", None, None, 0),
        (_JSET_K, "allow", "deny", _CLONE_THREAD),       # a thread shares the address space: allowed
        ("deny", None, None, 0),
        (_RET_K, None, None, _RET_ERRNO | errno.EACCES),
        ("enosys", None, None, 0),
        (_RET_K, None, None, _RET_ERRNO | errno.ENOSYS),
        ("allow", None, None, 0),
        (_RET_K, None, None, _RET_ALLOW),
    ]
    labels: dict[str, int] = {}
    insns: list[tuple[int, str | None, str | None, int]] = []
    for op, jt, jf, k in code:
        if isinstance(op, str):
            labels[op] = len(insns)
        else:
            insns.append((op, jt, jf, k))
    out = []
    for i, (op, jt, jf, k) in enumerate(insns):
        # a jump lands on (its index + 1 + offset)
        t = labels[jt] - i - 1 if jt else 0
        f = labels[jf] - i - 1 if jf else 0
        out.append(struct.pack("HBBI", op, t, f, k))
    return b"".join(out)


def available() -> bool:
    """True where the filter can be installed: Linux on a known machine."""
    return sys.platform.startswith("linux") and program() is not None


def install() -> bool:
    """Install the filter on this process (inherited by its children, irrevocable). False if unsupported."""
    prog = program()
    if prog is None or not available():
        return False
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl.argtypes = [ctypes.c_int, ctypes.c_ulong, ctypes.c_void_p, ctypes.c_ulong, ctypes.c_ulong]
    buf = ctypes.create_string_buffer(prog, len(prog))

    class SockFprog(ctypes.Structure):
        _fields_ = [("len", ctypes.c_ushort), ("filter", ctypes.c_void_p)]

    fprog = SockFprog(len(prog) // 8, ctypes.addressof(buf))
    if libc.prctl(_PR_SET_NO_NEW_PRIVS, 1, None, 0, 0) != 0:
        return False
    if libc.prctl(_PR_SET_SECCOMP, _SECCOMP_MODE_FILTER, ctypes.addressof(fprog), 0, 0) != 0:
        return False
    return True
