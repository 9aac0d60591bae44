"""A small seccomp filter the worker installs on itself: no network sockets, in every isolation mode.

bubblewrap already gives the worker an empty network namespace; without bubblewrap this filter is what
keeps student code off the network. It allows every system call except socket() for any family but
AF_UNIX (errno EACCES), io_uring_setup (which could open sockets behind the filter's back) and any call
through a foreign ABI (x32, or 32-bit int 0x80 on x86-64, which would reach socketcall), all ENOSYS/EACCES.
Only x86-64 and aarch64 are known; elsewhere nothing is installed and `install()` returns False.
"""

from __future__ import annotations

import ctypes
import errno
import platform
import struct

_PR_SET_NO_NEW_PRIVS = 38
_PR_SET_SECCOMP = 22
_SECCOMP_MODE_FILTER = 2
_RET_ALLOW = 0x7FFF0000
_RET_ERRNO = 0x00050000
_AF_UNIX = 1
# machine -> (AUDIT_ARCH, __NR_socket, __NR_io_uring_setup, first foreign-ABI syscall number or None)
_ARCHES = {
    "x86_64": (0xC000003E, 41, 425, 0x40000000),
    "aarch64": (0xC00000B7, 198, 425, None),
}

# classic BPF opcodes
_LD_W_ABS = 0x20
_JEQ_K = 0x15
_JGE_K = 0x35
_RET_K = 0x06


def _insn(code: int, jt: int, jf: int, k: int) -> bytes:
    return struct.pack("HBBI", code, jt, jf, k)


def program(machine: str | None = None) -> bytes | None:
    """The filter for `machine` (default: this one) as packed sock_filter entries, or None if unknown."""
    arch = _ARCHES.get(machine or platform.machine())
    if arch is None:
        return None
    audit_arch, nr_socket, nr_io_uring, foreign = arch
    deny = _RET_ERRNO | errno.EACCES
    insns = [
        _insn(_LD_W_ABS, 0, 0, 4),                      # 0: A = arch
        _insn(_JEQ_K, 1, 0, audit_arch),                # 1: native ABI? go on : deny
        _insn(_RET_K, 0, 0, _RET_ERRNO | errno.ENOSYS),  # 2: foreign ABI (i386 socketcall...)
        _insn(_LD_W_ABS, 0, 0, 0),                      # 3: A = syscall number
        _insn(_JGE_K, 5, 0, foreign if foreign is not None else 0xFFFFFFFF),  # 4: x32 ABI -> 10
        _insn(_JEQ_K, 2, 0, nr_socket),                 # 5: socket -> 8
        _insn(_JEQ_K, 3, 0, nr_io_uring),               # 6: io_uring_setup -> 10
        _insn(_RET_K, 0, 0, _RET_ALLOW),                # 7: everything else
        _insn(_LD_W_ABS, 0, 0, 16),                     # 8: A = low word of args[0] (the family)
        _insn(_JEQ_K, 1, 0, _AF_UNIX),                  # 9: AF_UNIX -> 11
        _insn(_RET_K, 0, 0, deny),                      # 10: other families, io_uring, x32
        _insn(_RET_K, 0, 0, _RET_ALLOW),                # 11
    ]  # a jump goes to (its index + 1 + offset)
    return b"".join(insns)


def install() -> bool:
    """Install the filter on this process (inherited by its children, irrevocable). False if unsupported."""
    prog = program()
    if prog is None:
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
