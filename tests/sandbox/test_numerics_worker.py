"""Issue 20: the worker runs student code in the official numeric environment, in both isolation modes,
and reports what it loaded (before any student code runs); the grading process records that report.

The control: with the pin undone (SIMIAM_BLAS_KERNEL=native) a CPU with AVX-512 gets other bits from the
same student code, and the report says the run is not official."""

from __future__ import annotations

import numpy as np
import pytest
from sandbox_helpers import attack

from simiam import numerics

X = [-1.608187784186389, 0.2417718768768513]
Y = [0.23538091873745476, 1.5756260314314627]
HASWELL_CPU = numerics.official_kernel(numerics.cpu_flags()) == numerics.OFFICIAL_KERNEL
AVX512_CPU = "avx512f" in (numerics.cpu_flags() or ())


def here() -> dict:
    """The same products in this (pinned) test process: what official grading computes."""
    x, y = np.array(X), np.array(Y)
    T = np.array([[x[0], -x[1], 0.3], [x[1], x[0], -0.7], [0.0, 0.0, 1.0]])
    points = np.array([[y[0], y[1], 0.5, -0.25, 1.5], [y[1], -y[0], 0.75, 0.125, -1.0], [1.0] * 5])
    return {"dot": float(x @ y).hex(), "gemm": [float(v).hex() for v in (T @ points).ravel()],
            "atan2": float(np.arctan2(x[0] * 1.7, y[1] - 0.3)).hex()}


@pytest.mark.skipif(not HASWELL_CPU, reason="the official kernel needs AVX2 and FMA")
def test_student_products_in_the_worker_are_the_official_bits(open_session, mode, monkeypatch) -> None:
    monkeypatch.setenv("OPENBLAS_CORETYPE", "SkylakeX")  # the grader's shell does not choose the worker's
    session = open_session("blas_products")
    assert attack(session, x=X, y=Y) == here()
    assert session.numerics["official"] is True and session.numerics["kernel"] == "Haswell"
    assert session.numerics["threads"] == 1 and "AVX512" not in str(session.numerics["numpy_simd"])


def test_another_kernel_is_reported_as_not_official(open_session, mode, monkeypatch) -> None:
    monkeypatch.setenv(numerics.OVERRIDE, "Sandybridge")
    session = open_session("blas_products")
    attack(session, x=X, y=Y)
    assert session.numerics["kernel"] == "Sandybridge" and session.numerics["official"] is False
    assert numerics.DIFFERS in str(session.numerics["note"])


@pytest.mark.skipif(not AVX512_CPU, reason="the other bits show only on a CPU with AVX-512")
def test_without_the_pin_the_same_code_gets_other_bits(open_session, mode, monkeypatch) -> None:
    monkeypatch.setenv(numerics.OVERRIDE, "native")
    session = open_session("blas_products")
    assert attack(session, x=X, y=Y)["dot"] != here()["dot"]
    assert session.numerics["official"] is False and "AVX-512" in str(session.numerics["note"])
