"""Issue 20: the grader's side of every comparison is the same on every CPU.

Trusted code (the physics, the checks, the reference maths, the probes, the instructor tools) uses plain
float arithmetic and the C library's math: never numpy's `@`, `np.dot` or `np.linalg` (handed to the BLAS
kernel the CPU picks, some of which fuse a multiply and an add) nor numpy's transcendental functions (on
AVX-512 numpy uses other loops for `np.arctan2`, `np.exp`, ...). The walk below reads every trusted module's
syntax tree; the planted snippets prove it sees each form.
"""

from __future__ import annotations

import ast
import math
import random
from fractions import Fraction
from pathlib import Path

import pytest

from grader import reference

REPO = Path(__file__).resolve().parents[2]
TRUSTED = [p for folder in ("simiam", "grader", "instructor_tools")
           for p in sorted((REPO / folder).rglob("*.py"))
           if "skeletons" not in p.parts and "compiled" not in p.parts]
NUMPY_NAMES = {"np", "numpy"}
KERNEL_DEPENDENT = {
    "dot", "matmul", "inner", "vdot", "tensordot", "einsum", "outer", "linalg", "kron",
    "sin", "cos", "tan", "arcsin", "arccos", "arctan", "arctan2", "sinh", "cosh", "tanh", "arcsinh",
    "arccosh", "arctanh", "exp", "exp2", "expm1", "log", "log2", "log10", "log1p", "power", "float_power",
    "cbrt", "polyval",
}


def kernel_dependent_uses(source: str) -> list[str]:
    """Where `source` does arithmetic whose last bit depends on the CPU's BLAS kernel or numpy's loops."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.BinOp, ast.AugAssign)) and isinstance(node.op, ast.MatMult):
            found.append(f"line {node.lineno}: @")
        elif (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
              and node.value.id in NUMPY_NAMES and node.attr in KERNEL_DEPENDENT):
            found.append(f"line {node.lineno}: {node.value.id}.{node.attr}")
        elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "numpy":
            names = {alias.name for alias in node.names}
            if (node.module or "").startswith("numpy.linalg") or names & KERNEL_DEPENDENT:
                found.append(f"line {node.lineno}: from {node.module} import {', '.join(sorted(names))}")
    return found


@pytest.mark.parametrize("path", TRUSTED, ids=lambda p: str(p.relative_to(REPO)))
def test_trusted_code_does_no_kernel_dependent_arithmetic(path: Path) -> None:
    assert kernel_dependent_uses(path.read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("snippet", [
    "residual = np.array(rows) @ gains",
    "m @= other",
    "towards = float(np.dot(u, v))",
    "gains = numpy.linalg.lstsq(a, b)",
    "theta = np.arctan2(y, x)",
    "from numpy.linalg import solve",
    "from numpy import dot",
    "y = np.polyval(coeff, v)",
])
def test_the_walk_sees_each_form(snippet: str) -> None:
    assert kernel_dependent_uses(snippet) != []


def test_the_walk_lets_plain_arithmetic_and_array_building_pass() -> None:
    assert kernel_dependent_uses("x = np.array([1.0, 2.0]) * 3 + math.atan2(y, x)\nz = a @ 'b' if 0 else 1") \
        == ["line 2: @"]
    assert kernel_dependent_uses("u = np.zeros(3); m = max(np.abs(u)); t = math.sin(a) * b") == []


def test_dot_sums_left_to_right_without_fusing() -> None:
    rng = random.Random(20)
    for _ in range(2000):
        u = [rng.uniform(-2, 2) for _ in range(rng.choice([2, 3, 5]))]
        v = [rng.uniform(-2, 2) for _ in u]
        expected = 0.0
        for a, b in zip(u, v, strict=True):
            expected = float(Fraction(expected) + Fraction(a * b))  # each product rounded, then each sum
        assert reference.dot(u, v) == expected
    # the issue's example: fused (AVX-512's kernel) and plain differ in the last bit; plain is what we keep
    x, y = [-1.608187784186389, 0.2417718768768513], [0.23538091873745476, 1.5756260314314627]
    assert reference.dot(x, y).hex() == "0x1.3b45f9e93b980p-9"


def test_least_squares_is_the_exact_rational_solution_rounded_once() -> None:
    rng = random.Random(21)
    for _ in range(50):
        truth = [rng.uniform(-1, 1) for _ in range(5)]
        rows = [[rng.uniform(-1, 1) for _ in range(5)] for _ in range(12)]
        rhs = [reference.dot(row, truth) for row in rows]
        got = reference.least_squares(rows, rhs)
        assert max(abs(g - t) for g, t in zip(got, truth, strict=True)) < 1e-12
        # the residual's gradient vanishes exactly at the rational optimum: Aᵀ(Ax - b) ~ 0
        residual = [reference.dot(row, got) - b for row, b in zip(rows, rhs, strict=True)]
        assert all(abs(reference.dot([row[j] for row in rows], residual)) < 1e-13 for j in range(5))
    # inconsistent and singular: the mean of the two demands, the free unknown 0
    assert reference.least_squares([[1.0, 0.0], [1.0, 0.0]], [1.0, 3.0]) == [2.0, 0.0]
    assert not math.isnan(reference.least_squares([[0.0, 0.0]], [1.0])[0])
