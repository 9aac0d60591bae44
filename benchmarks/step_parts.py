"""Where one `simiam bench` step spends its CPU time: the brain, the command validation, the physics pass and
the rest (move, encoders, readings, limits, record), next to the same run's flat-loop baseline.

    python benchmarks/step_parts.py [--steps 1818] [--repeat 7]   (1818 steps: the 60 s of `simiam bench`)

Measured by substitution, in the step loop itself (the parts cost more there than one by one, where the
caches stay warm): the bench's run is recorded once, then stepped again with the brain replaced by a replay
of its answers, then also without validation (the answer passes as it is) and without physics (a constant
open-space answer). Each part is the difference between two of those runs, best of `--repeat`, thread CPU
time. A figure to read, not a test; on a shared machine compare the ratios.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

from simiam import bench
from simiam import simulator as simulator_module
from simiam.machine import load_after_line, machine_line
from simiam.physics.robot_surfaces import RobotSurfaces


class Replay:
    """The brain's recorded answers, one a step (the same objects: validation copies what it keeps)."""

    def __init__(self, answers: list[Any]) -> None:
        self.answers = answers
        self.k = -1

    def step(self, readings: dict) -> Any:
        self.k += 1
        return self.answers[self.k]


def cpu_per_step(make: Callable[[], simulator_module.Simulator], steps: int, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        sim = make()
        t0 = time.thread_time()
        for _ in range(steps):
            sim.step()
        best = min(best, time.thread_time() - t0)
    return best / steps * 1e6


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=1818)
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    print(machine_line("none (trusted code only)"))
    dt = 0.033
    sim = bench._simulator(dt)
    answers: list[Any] = []
    brain_step = sim.brain.step
    sim.brain.step = lambda readings: answers.append(brain_step(readings)) or answers[-1]  # type: ignore[method-assign]
    for _ in range(args.steps):
        sim.step()

    def replayed() -> simulator_module.Simulator:
        s = bench._simulator(dt)
        s.brain = Replay(answers)
        return s

    full = cpu_per_step(lambda: bench._simulator(dt), args.steps, args.repeat)
    replay = cpu_per_step(replayed, args.steps, args.repeat)
    validate = simulator_module.validate_command
    open_space = (False, (0.3,) * 5, (133,) * 5)
    physics = RobotSurfaces.step
    try:
        simulator_module.validate_command = lambda answer, *rest: answer  # type: ignore[assignment]
        no_validation = cpu_per_step(replayed, args.steps, args.repeat)
        RobotSurfaces.step = lambda self, pose: open_space  # type: ignore[method-assign]
        neither = cpu_per_step(replayed, args.steps, args.repeat)
    finally:
        simulator_module.validate_command = validate
        RobotSurfaces.step = physics  # type: ignore[method-assign]
    best_base = float("inf")
    for _ in range(args.repeat):
        t0 = time.thread_time()
        bench.baseline_steps(args.steps, dt)
        best_base = min(best_base, time.thread_time() - t0)
    base = best_base / args.steps * 1e6
    parts = {"brain (reference avoid-obstacles)": full - replay, "command validation": replay - no_validation,
             "physics pass (collision, IR)": no_validation - neither,
             "the rest (move, encoders, readings, limits, record; replay's own call)": neither}
    print(f"step, CPU us (week-4 world, {args.steps} steps, best of {args.repeat}): {full:.1f} "
          f"({full / base:.2f}x the flat-loop baseline, {base:.1f})")
    for name, us in parts.items():
        print(f"  {name}: {us:.1f} us ({us / base:.2f}x baseline)")
    print(load_after_line())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
