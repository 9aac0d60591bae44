"""simiam: the Sim.I.am QuickBot simulator in Python, and (in the sibling package `grader`) its autograder."""

from simiam import numerics

# Before anything imports numpy: one BLAS kernel, one thread, one SIMD level (simiam.numerics says why).
numerics.pin()

# The one place the version is written: pyproject.toml reads it (tool.setuptools.dynamic), and results
# carry it as grader_version without importing importlib.metadata.
__version__ = "0.1.0"
