"""The BLAS kernels this CPU can run, one per kernel OpenBLAS really loads, for proving verdicts robust.

A closed loop turns one last bit into another run, and the bits of `u @ v` or `np.linalg.solve` depend on the
OpenBLAS kernel (simiam.numerics). A verdict with a margin is one that no kernel flips. OpenBLAS takes a
kernel name in OPENBLAS_CORETYPE (simiam.numerics sets it from SIMIAM_BLAS_KERNEL) and quietly loads another
where the name is unknown or the CPU lacks the instructions (here Zen loads Haswell, Cooperlake SkylakeX,
Prescott "Katmai"), so the names are grouped by what `simiam.numerics.describe()` reports back in a fresh
process. "native" pins nothing at all: the CPU's own kernel and numpy's own (AVX-512) loops.

    python -m instructor_tools.kernels      # the groups on this machine

Used by instructor_tools/hidden_week7.py (variants the reference reaches under every kernel) and
tests/grader/test_verdict_margins.py (verdicts identical under every kernel).
"""

from __future__ import annotations

import functools
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from simiam.numerics import NATIVE, OFFICIAL_KERNEL, OVERRIDE

ROOT = Path(__file__).resolve().parents[1]
# OpenBLAS's x86-64 core names (driver/others/dynamic.c, force_coretype), oldest first
CORE_NAMES = ("Katmai", "Coppermine", "Northwood", "Prescott", "Banias", "Atom", "Core2", "Penryn",
              "Dunnington", "Nehalem", "Athlon", "Opteron", "Barcelona", "Nano", "Sandybridge", "Bobcat",
              "Bulldozer", "Piledriver", "Haswell", "Steamroller", "Excavator", "Zen", "SkylakeX",
              "Cooperlake", "SapphireRapids")
_PROBE = "import json, simiam.numerics as n, numpy; print(json.dumps(n.describe()))"


def environment(kernel: str) -> dict[str, str]:
    """This process's environment with SIMIAM_BLAS_KERNEL = `kernel` (a core name or "native"): what a
    child needs so that simiam pins that kernel before its numpy (and its sandbox workers' numpy) loads."""
    return {**os.environ, OVERRIDE: kernel}


def loaded(kernel: str) -> dict[str, object]:
    """simiam.numerics.describe() of a fresh process started with `kernel`."""
    done = subprocess.run([sys.executable, "-c", _PROBE], env=environment(kernel), capture_output=True,
                          text=True, check=True, cwd=ROOT)
    return json.loads(done.stdout)


@functools.cache
def groups() -> dict[str, tuple[str, ...]]:
    """{what loads: the names that load it}, official kernel first, "native" last (only where it is not the
    same as a pinned one: numpy's SIMD level differs from every pinned one on an AVX-512 CPU). Empty where
    numpy does not use OpenBLAS."""
    with ThreadPoolExecutor(max_workers=2) as pool:
        found = dict(zip(CORE_NAMES + (NATIVE,), pool.map(loaded, CORE_NAMES + (NATIVE,)), strict=True))
    if not found[OFFICIAL_KERNEL].get("kernel"):
        return {}
    out: dict[str, list[str]] = {}
    for name in CORE_NAMES:
        out.setdefault(str(found[name]["kernel"]), []).append(name)
    native = found[NATIVE]
    pinned = {(d["kernel"], d["numpy_simd"]) for n, d in found.items() if n != NATIVE}
    if (native["kernel"], native["numpy_simd"]) not in pinned:
        out[f"{native['kernel']} {NATIVE}"] = [NATIVE]
    official = str(found[OFFICIAL_KERNEL]["kernel"])
    order = [official] + [k for k in out if k != official]
    return {k: tuple(out[k]) for k in order}


def runnable() -> list[str]:
    """One name per distinct kernel, the one its group is run under (the kernel's own name where it is one
    of them), the official kernel first and "native" last."""
    return [loads if loads in names else names[0] for loads, names in groups().items()]


def loads(name: str) -> str:
    """The kernel OpenBLAS loads for `name` here (what describe() reports)."""
    return next(key.split()[0] for key, names in groups().items() if name in names)


if __name__ == "__main__":
    for loads, names in groups().items():
        print(f"{loads:24} {', '.join(names)}")
