"""simiam: the Sim.I.am QuickBot simulator in Python, and (in the sibling package `grader`) its autograder."""

# The one place the version is written: pyproject.toml reads it (tool.setuptools.dynamic), and results
# carry it as grader_version without importing importlib.metadata.
__version__ = "0.1.0"
