"""WRONG VERSION (tests/sandbox/test_inside.py): what is planted at the end of grader/inside/probes.py: an import of the simulator's physics planted."""


def _cheat():
    from simiam.robot.dynamics import move
    return move
