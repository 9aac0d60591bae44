"""WRONG VERSION (tests/sandbox/test_inside.py): what is planted at the end of grader/inside/probes.py: a nested relative import of the checks' maths planted."""


def _cheat():
    from .. import reference
    return reference
