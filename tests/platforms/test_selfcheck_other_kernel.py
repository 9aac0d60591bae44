"""Issue 20: `grade selfcheck` (every week: solutions full marks, stubs zero, each kept wrong version
losing exactly its aims) holds when the shell asked for another BLAS kernel, more threads and numpy's
AVX-512 loops: simiam pins its own environment (simiam.numerics), in the grading process and in every
worker. The default-kernel run is the rest of the suite (tests/grader/test_checks_fail.py and friends)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from simiam import numerics

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_selfcheck_holds_under_a_shell_that_chose_another_kernel() -> None:
    ours = (*numerics.PINNED_VARIABLES, numerics.OVERRIDE)
    environ = {k: v for k, v in os.environ.items() if k not in ours}
    environ.update(OPENBLAS_CORETYPE="Sandybridge", OPENBLAS_NUM_THREADS="2", NPY_DISABLE_CPU_FEATURES="")
    done = subprocess.run([sys.executable, "-m", "grader.cli", "selfcheck", "--course", str(ROOT)],
                          capture_output=True, text=True, cwd=ROOT, env=environ, timeout=1800)
    # the FAIL lines and what follows each (its margins), wherever they are in the long output, then the end
    failed, within = [], False
    for line in done.stdout.splitlines():
        within = line.startswith("FAIL") or (within and line.startswith(" "))
        if within:
            failed.append(line)
    assert done.returncode == 0, "\n".join(failed)[:6000] + "\n...\n" + (done.stdout + done.stderr)[-1500:]
    assert done.stdout.rstrip().splitlines()[-1] == "selfcheck: all expectations held"
