"""`Fleet`: several QuickBots in one world, each driven by its own Brain, that see and hit each other.

The original's `Simulator.step` with more than one robot: every robot moves and runs its supervisor, then
one physics pass checks each base plate against the obstacles and the *other robots'* base plates; if any
robot collided, no IR sensor is updated in that step (the original's `apply_physics` returns at the first
collision), otherwise every robot's IR cones range against the obstacles and the other robots' plates.
A single robot needs none of this: use `Simulator` directly.

    fleet = Fleet(load_world("week3"), [(brain_a, spec, (0, 0, 0)), (brain_b, spec, (0.5, 0, 3.14))])
    records = fleet.step()              # one StepRecord per robot
    fleet.robots[1].pose                # each robot is a Simulator: pose, ticks, ir_raw, collided, ...
    traces = fleet.run(seconds=10)      # one Trace per robot, through the simulator's one step loop
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from simiam.robot.quickbot import RobotSpec
from simiam.signals import WEEKS_1_TO_4
from simiam.simulator import Brain, Simulator, StepRecord, run_steps
from simiam.trace import Trace
from simiam.world.world import World

Pose = tuple[float, float, float]


class Fleet:
    """Robots `(brain, spec, start pose)` in `world`, stepped together at a fixed dt."""

    def __init__(self, world: World, robots: Sequence[tuple[Brain, RobotSpec, Pose]],
                 dt: float = 0.033, signals: Sequence[str] = WEEKS_1_TO_4) -> None:
        if not robots:
            raise ValueError("a Fleet needs at least one robot")
        self.robots = [Simulator(world, brain, spec, dt=dt, start=start, signals=signals)
                       for brain, spec, start in robots]
        # the construction pass of the original, now with the other robots in view
        self._physics()
        for sim in self.robots:
            sim._finish(None)

    def step(self) -> list[StepRecord]:
        """Advance every robot one step; returns their records in order."""
        commands = [sim._advance() for sim in self.robots]
        self._physics()
        return [sim._finish(command) for sim, command in zip(self.robots, commands, strict=True)]

    def run(self, seconds: float, stop_on_collision: bool = True,
            until: Callable[[list[StepRecord]], bool] | None = None,
            stuck: tuple[type[BaseException], ...] = ()) -> list[Trace]:
        """Step every robot for `seconds` (the loop of `Simulator.run`): one Trace per robot, all ending
        together, at the first collision of any robot (unless `stop_on_collision` is false), once
        `until(records)` is true, or when a brain breaks (its Ending names the robot)."""
        return run_steps(self.robots, self.step, seconds, stop_on_collision, until, stuck)

    def _physics(self) -> None:
        plates = [sim.plate_polygon() for sim in self.robots]
        others = [plates[:i] + plates[i + 1:] for i in range(len(plates))]
        hits = [sim._collide(o) for sim, o in zip(self.robots, others, strict=True)]
        if not any(hits):
            for sim, o in zip(self.robots, others, strict=True):
                sim._update_ir(o)
