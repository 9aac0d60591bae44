"""WRONG Fleet: steps each robot's Simulator on its own, so the robots neither see nor hit each other."""
from simiam.simulator import Simulator


class Fleet:
    def __init__(self, world, robots, dt=0.033):
        self.robots = [Simulator(world, brain, spec, dt=dt, start=start) for brain, spec, start in robots]

    def step(self):
        return [sim.step() for sim in self.robots]
