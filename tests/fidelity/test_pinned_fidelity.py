"""Issue 20: the fidelity tests pass whatever kernel the shell chose, because simiam pins its own.

CI runs the suite under the machine's default kernel; this runs the fidelity tests again in a fresh
pytest whose shell asks for another kernel (Sandybridge: the golden runs fail under it, see the control),
so a pin that stops working fails CI on any CPU. The control proves the fidelity tests see a kernel at all.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from simiam import numerics

REPO = Path(__file__).resolve().parents[2]
HERE = Path(__file__).relative_to(REPO)
CONTROL = ["tests/fidelity/test_follow_wall_closed_loop.py", "tests/fidelity/test_week7_fsm.py"]
pytestmark = pytest.mark.skipif(numerics.official_kernel(numerics.cpu_flags()) != numerics.OFFICIAL_KERNEL,
                                reason="the official kernel needs an x86-64 CPU with AVX2 and FMA")


def fidelity(paths: list[str], **env: str) -> subprocess.CompletedProcess:
    ours = (*numerics.PINNED_VARIABLES, numerics.OVERRIDE)
    environ = {k: v for k, v in os.environ.items() if k not in ours and not k.startswith("PYTEST_")}
    environ.update(env)
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-n", "0", "-p", "no:cacheprovider",
                           "--ignore", str(HERE), *paths], capture_output=True, text=True, cwd=REPO,
                          env=environ, timeout=900)


def test_the_fidelity_tests_pass_when_the_shell_chose_another_kernel() -> None:
    done = fidelity(["tests/fidelity"], OPENBLAS_CORETYPE="Sandybridge", NPY_DISABLE_CPU_FEATURES="",
                    OPENBLAS_NUM_THREADS="2")
    assert done.returncode == 0, done.stdout[-3000:]
    assert " passed" in done.stdout and " failed" not in done.stdout


def test_control_the_fidelity_tests_fail_under_another_kernel_chosen_by_simiam() -> None:
    done = fidelity(["-x", *CONTROL], SIMIAM_BLAS_KERNEL="Sandybridge")  # one failure is the proof
    assert done.returncode == 1 and " failed" in done.stdout, done.stdout[-3000:]
