"""A platform's container, as near as a test can make one: a private mount namespace (bubblewrap) where
temporary folders are bound at the platform's own paths (/autograder, /grade, /opt/simiam-venv, ...), the
host's /usr and /etc are read-only, /tmp is private and the PID namespace its own; commands run as root
with a plain environment, as Gradescope and PrairieLearn run their scripts.

Two kinds of container:

- `namespaces=True`: root keeps its capabilities, so the grader's own bubblewrap can create its namespaces
  inside (an image where the platform allows them);
- `namespaces=False`: only Docker's default capabilities are kept (no CAP_SYS_ADMIN), so the grader's
  bubblewrap fails as it does in a Docker container started with the defaults ("Creating new namespace
  failed: Operation not permitted"). Docker's seccomp profile, which also refuses new user namespaces, is
  not replayed: the grader runs as root there and never asks bubblewrap for a user namespace, so the
  capability set alone decides, and the grader's own capability probe (isolation.bwrap_works) sees that.

The platform's Python is the host's /usr/bin/python3 (a Debian python3 with venv, as in the PrairieLearn
image's debian:bookworm-slim); the apt step of setup.sh is skipped (SIMIAM_SKIP_APT=1): it would install
what is already there. pip reaches the package index from the host's network settings (NETWORK_ENV); the
layout test fetches the dependencies once into a wheelhouse that both images install from.
"""

from __future__ import annotations

import functools
import os
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

# Docker's default capability set (moby's oci/caps/defaults.go)
DOCKER_CAPS = ("CHOWN", "DAC_OVERRIDE", "FSETID", "FOWNER", "MKNOD", "NET_RAW", "SETGID", "SETUID", "SETFCAP",
               "SETPCAP", "NET_BIND_SERVICE", "SYS_CHROOT", "KILL", "AUDIT_WRITE")
PYTHON = "/usr/bin/python3"
# how this host reaches the package index (certificates, proxies, timeouts): a platform's build has its own
NETWORK_ENV = ("PIP_CERT", "PIP_DEFAULT_TIMEOUT", "PIP_INDEX_URL", "PIP_EXTRA_INDEX_URL", "SSL_CERT_FILE",
               "SSL_CERT_DIR", "REQUESTS_CA_BUNDLE", "http_proxy", "https_proxy", "HTTP_PROXY", "HTTPS_PROXY",
               "no_proxy", "NO_PROXY")


@functools.lru_cache(maxsize=1)
def usable() -> str:
    """Why containers cannot be made here ("" when they can): bubblewrap as root, and a Debian-like
    /usr/bin/python3 with venv, as the platforms' images have."""
    if os.geteuid() != 0 or shutil.which("bwrap") is None:
        return "needs bubblewrap, run as root (as the platforms run their scripts)"
    code = "import sys, venv, ensurepip; sys.exit(sys.version_info < (3, 10))"
    probe = subprocess.run([PYTHON, "-c", code], capture_output=True) if os.path.exists(PYTHON) else None
    if probe is None or probe.returncode != 0:
        return f"needs {PYTHON} (3.10 or newer, with venv and ensurepip) as a platform image has"
    try:
        subprocess.run(["bwrap", "--ro-bind", "/", "/", "--", "true"], check=True, capture_output=True)
    except (OSError, subprocess.CalledProcessError):
        return "bubblewrap cannot create a namespace here"
    return ""


@dataclass
class Container:
    """Folders of this host bound read-write at paths of the container (`binds`: inside path -> host)."""

    binds: dict[str, Path]
    namespaces: bool
    extra_caps: tuple[str, ...] = ()   # added to Docker's defaults (docs/platforms.md names them)

    def argv(self) -> list[str]:
        args = ["bwrap", "--die-with-parent", "--unshare-pid", "--ro-bind", "/usr", "/usr"]
        for top in ("/bin", "/sbin", "/lib", "/lib64", "/lib32"):
            if os.path.islink(top):
                args += ["--symlink", os.readlink(top), top]
            elif os.path.isdir(top):
                args += ["--ro-bind", top, top]
        args += ["--ro-bind", "/etc", "/etc", "--proc", "/proc", "--dev", "/dev", "--tmpfs", "/tmp",
                 "--tmpfs", "/root", "--tmpfs", "/usr/local"]   # nothing of this host's /usr/local
        for inside, host in sorted(self.binds.items()):
            args += ["--bind", str(host), inside]
        if not self.namespaces:
            caps = DOCKER_CAPS + self.extra_caps
            args += ["--cap-drop", "ALL"] + [a for cap in caps for a in ("--cap-add", f"CAP_{cap}")]
        return args + ["--clearenv", "--setenv", "PATH", "/usr/local/bin:/usr/bin:/bin", "--setenv", "HOME",
                       "/root", "--setenv", "LANG", "C.UTF-8", "--chdir", "/"]

    def run(self, command: list[str], env: dict[str, str] | None = None,
            timeout: float = 900) -> subprocess.CompletedProcess:
        env = {**{k: os.environ[k] for k in NETWORK_ENV if k in os.environ}, **(env or {})}
        extra = [a for key, value in env.items() for a in ("--setenv", key, value)]
        return subprocess.run([*self.argv(), *extra, "--", *command], capture_output=True, text=True,
                              timeout=timeout)
