"""Issue 20: one numeric environment wherever controller code runs (simiam.numerics).

The pin is proven where it matters: a fresh interpreter whose shell chose another kernel still computes the
official bits once simiam is imported; a worker reports the kernel it really loaded; a result says so when
the environment is not official grading's. Every subprocess here starts from an environment that would give
other bits without the pin (OPENBLAS_CORETYPE=SkylakeX on a CPU that has it, numpy's AVX-512 loops on).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from simiam import numerics

REPO = Path(__file__).resolve().parents[2]
HASWELL_CPU = numerics.official_kernel(numerics.cpu_flags()) == numerics.OFFICIAL_KERNEL
AVX512_CPU = "avx512f" in (numerics.cpu_flags() or ())
# the smallest example: x @ y rounds differently under the AVX-512 kernel
X = [-1.608187784186389, 0.2417718768768513]
Y = [0.23538091873745476, 1.5756260314314627]
OFFICIAL_BITS = "0x1.3b45f9e93b980p-9"
SHOW = ("import json, simiam, numpy as np; from simiam.numerics import describe; "
        f"d = describe(); d['dot'] = float(np.array({X}) @ np.array({Y})).hex(); print(json.dumps(d))")


def run_python(code: str, **env: str) -> dict:
    """Run `code` in a fresh interpreter with the shell's numeric variables replaced by `env`."""
    ours = (*numerics.PINNED_VARIABLES, numerics.OVERRIDE)
    environ = {k: v for k, v in os.environ.items() if k not in ours}
    environ.update(env, PYTHONPATH=str(REPO))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=environ,
                          cwd=REPO, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_plan_pins_haswell_with_avx2_and_fma_and_falls_back_without() -> None:
    modern = frozenset({"avx2", "fma", "sse4_2", "avx512f"})
    assert numerics.plan({}, modern)["OPENBLAS_CORETYPE"] == "Haswell"
    assert numerics.plan({}, frozenset({"sse4_2", "avx"}))["OPENBLAS_CORETYPE"] == "Nehalem"
    assert "OPENBLAS_CORETYPE" not in numerics.plan({}, frozenset({"sse2"}))
    for variables in (numerics.plan({}, modern), numerics.plan({}, frozenset())):
        assert all(variables[name] == "1" for name in numerics.THREAD_VARIABLES)
    chosen = numerics.plan({numerics.OVERRIDE: "Sandybridge"}, modern)
    assert chosen["OPENBLAS_CORETYPE"] == "Sandybridge" and chosen[numerics.OVERRIDE] == "Sandybridge"
    assert numerics.plan({numerics.OVERRIDE: "native"}, modern) == {numerics.OVERRIDE: "native"}


@pytest.mark.skipif(not HASWELL_CPU, reason="the official kernel needs AVX2 and FMA")
@pytest.mark.parametrize("shell", [{}, {"OPENBLAS_CORETYPE": "SkylakeX", "OPENBLAS_NUM_THREADS": "2",
                                       "NPY_DISABLE_CPU_FEATURES": ""},
                                   {"OPENBLAS_CORETYPE": "Sandybridge"}])
def test_importing_simiam_pins_the_official_environment_whatever_the_shell_set(shell: dict) -> None:
    seen = run_python(SHOW, **shell)
    assert (seen["kernel"], seen["threads"], seen["official"], seen["note"]) == ("Haswell", 1, True, "")
    assert "AVX512" not in seen["numpy_simd"] and "X86_V4" not in seen["numpy_simd"]
    assert seen["dot"] == OFFICIAL_BITS


@pytest.mark.skipif(not AVX512_CPU, reason="the other bits show only on a CPU with AVX-512")
def test_without_the_pin_this_cpu_computes_other_bits_and_says_so() -> None:
    """The control: the same code with the pin undone (native) gets the AVX-512 kernel's bits, and
    describe() says that runs can differ from official grading."""
    seen = run_python(SHOW, SIMIAM_BLAS_KERNEL="native")
    assert seen["dot"] != OFFICIAL_BITS
    assert seen["official"] is False and numerics.DIFFERS in seen["note"]


def test_numpy_imported_before_simiam_is_reported_not_hidden() -> None:
    code = "import numpy, json, simiam; from simiam.numerics import describe; print(json.dumps(describe()))"
    seen = run_python(code, OPENBLAS_CORETYPE="Prescott")
    assert seen["official"] is False
    assert "Prescott" in seen["note"] or "Katmai" in seen["note"]  # OpenBLAS's own name for that kernel
    assert "imported before simiam" in seen["note"]


@pytest.mark.parametrize("hostile", [
    None, "official", ["official"], {"official": "yes"}, {"official": True, "note": "x" * 10_000},
    {"official": True, "threads": True, "kernel": 7}, {"official": True, "kernel": "k" * 10_000},
])
def test_a_reported_environment_is_bounded_and_never_official_when_malformed(hostile: object) -> None:
    got = numerics.checked(hostile)
    assert got["official"] is False and got["note"]
    assert all(len(v) <= 600 for v in got.values() if isinstance(v, str))
    assert got.get("threads") in (None, 1) or isinstance(got.get("threads"), int)


def test_a_well_formed_official_report_stays_official() -> None:
    report = {"machine": "x86_64", "numpy": "2.4", "blas": "OpenBLAS", "kernel": "Haswell", "threads": 1,
              "numpy_simd": "X86_V3", "official": True, "note": ""}
    assert numerics.checked(report) == report
