"""The seccomp filter, installed in a throw-away interpreter (it cannot be removed once installed)."""

from __future__ import annotations

import struct
import subprocess
import sys
from pathlib import Path

import pytest

import grader
from grader.inside import seccomp

PROBE = """
import ctypes, os, socket, subprocess, sys, threading
sys.path[:0] = {paths!r}
from grader.inside.seccomp import install
assert install()
results = []
for family in (socket.AF_INET, socket.AF_INET6, socket.AF_NETLINK, socket.AF_PACKET):
    try:
        socket.socket(family, socket.SOCK_DGRAM if family != socket.AF_PACKET else socket.SOCK_RAW).close()
        results.append("open")
    except PermissionError:
        results.append("denied")
a, b = socket.socketpair(socket.AF_UNIX)
a.sendall(b"x"); results.append(b.recv(1).decode())
libc = ctypes.CDLL(None, use_errno=True)
results.append("unshare " + str(libc.unshare(0x10000000) == -1 and ctypes.get_errno() == 13))
box = []
t = threading.Thread(target=lambda: box.append("thread")); t.start(); t.join(); results += box
try:
    pid = os.fork()
    if pid == 0:
        os._exit(7)
    results.append("fork " + str(os.waitpid(pid, 0)[1] >> 8))
except PermissionError:
    results.append("fork denied")
try:
    results.append(subprocess.run(["/bin/echo", "exec"], capture_output=True, text=True).stdout.strip())
except PermissionError:
    results.append("spawn denied")
print(",".join(results))
"""


@pytest.mark.skipif(seccomp.program() is None, reason="no filter for this machine")
def test_no_network_no_namespaces_no_processes_but_threads_work():
    paths = [str(Path(grader.__file__).parents[1])]
    done = subprocess.run([sys.executable, "-I", "-c", PROBE.format(paths=paths)], capture_output=True,
                          text=True, timeout=30)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "denied,denied,denied,denied,x,unshare True,thread,fork denied,spawn denied"


def test_jumps_stay_inside_the_program():
    for machine in ("x86_64", "aarch64"):
        prog = seccomp.program(machine)
        count = len(prog) // 8
        for i in range(count):
            code, jt, jf, _k = struct.unpack_from("HBBI", prog, 8 * i)
            if code in (0x15, 0x35):
                assert i + 1 + jt < count and i + 1 + jf < count
        assert struct.unpack_from("HBBI", prog, 8 * (count - 1))[0] == 0x06  # ends in a return
    assert seccomp.program("sparc") is None
