"""WRONG step order: the brain sees IR values computed after this step's move (the original's are one
step old)."""
from simiam.simulator import Simulator


class FreshIRSimulator(Simulator):
    def _move(self):
        super()._move()
        self._update_ir()


class NoDelaySimulator(Simulator):
    """Applies the brain's command in the same step (thinks before moving), as only week 1 does."""

    def step(self):
        self._k += 1
        command = self._think(self._k * self.dt)
        self._move()
        self._collided = self._check_collision()
        if not self._collided:
            self._update_ir()
        self._last = self._record(command)
        return self._last
