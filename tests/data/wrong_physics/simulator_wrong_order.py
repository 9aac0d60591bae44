"""WRONG step order: the brain sees IR values computed after this step's move (the original's are one
step old)."""
from simiam.simulator import Simulator


class FreshIRSimulator(Simulator):
    def _move(self):
        super()._move()
        self._update_ir()
