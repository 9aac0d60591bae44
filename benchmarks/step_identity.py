"""Every float the simulator produces, bit for bit, before and after a change to the step (issue 24).

    python benchmarks/step_identity.py record OUT.json.gz [--quick] [--only TEXT]
    python benchmarks/step_identity.py compare OUT.json.gz [--quick] [--only TEXT]

`record` runs the scenarios below and writes every trace (every column of every step, the collision and
the ending; floats as float.hex, so -0.0 and the last bit count) to OUT; `compare` runs them again and
prints the first difference of each scenario that differs (exit 1), or that all are identical (exit 0).
Record on the commit before the change, compare on the one after; run both also under
OPENBLAS_CORETYPE=Sandybridge (the students' numpy calls; the simulator itself uses plain Python floats).

The scenarios: the solutions of weeks 1-7 (`simiam run`'s setup: LocalBrain, the week's world, signals
and length) from the world's start and from starts nudged by 1e-9 m or rad; every kept wrong version
(tests/data/wrong/*.patch, applied as the tests apply them) from the start and nudged; the trusted
reference brains and constant wheel speeds from seeded random starts in the obstacle worlds, run on past
collisions (so the collision path and the exact boundary path run too); a Fleet of two; and `simiam run
weekN --solutions` itself (its trace JSON, less the folder it names). It prints how many times the exact
(fused-arithmetic) path ran, so that a comparison that never reached it is seen to be one.
Takes about 1-3 minutes on 2 cores (`--quick`: the solutions, the reference brains and the Fleet only;
`--only TEXT`: the scenarios whose name holds TEXT, e.g. `solution/week3`).
"""

from __future__ import annotations

import argparse
import gzip
import json
import math
import random
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import simiam  # noqa: F401  (before numpy: it pins the BLAS kernel)
from grader.platforms.wrong_versions import apply_mistake
from simiam.control.local_brain import LocalBrain
from simiam.course.folders import instructor_tool
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week, spec_for_week
from simiam.fleet import Fleet
from simiam.physics import robot_surfaces
from simiam.signals import week_signals
from simiam.simulator import ConstantBrain, Simulator
from simiam.trace import Trace
from simiam.world import World, load_world

ROOT = Path(__file__).resolve().parents[1]
WRONG = ROOT / "tests" / "data" / "wrong"
NUDGES = {"start": (0.0, 0.0, 0.0), "dx": (1e-9, 0.0, 0.0), "dy": (0.0, -1e-9, 0.0), "dth": (0.0, 0.0, 1e-9)}

Scenario = Callable[[], list[Trace]]


def plain(value: Any) -> Any:
    """JSON with every float as float.hex (bit-exact, -0.0 and NaN included)."""
    if isinstance(value, float):
        return value.hex()
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if hasattr(value, "value"):  # an Enum
        return plain(value.value)
    return value


def record_of(trace: Trace) -> dict:
    return plain({"steps": trace.steps, "collision": trace.collision, "start": trace.start,
                  "ending": None if trace.ending is None else trace.ending.to_json()})


def _moved(pose: tuple[float, float, float], nudge: tuple[float, float, float]) -> tuple[float, float, float]:
    return (pose[0] + nudge[0], pose[1] + nudge[1], pose[2] + nudge[2])


def course_run(folder: Path, week_number: int, nudge: tuple[float, float, float]) -> Scenario:
    """`simiam run`'s setup on `folder`, in process: the student's supervisor as a LocalBrain."""
    def run() -> list[Trace]:
        week = get_week(week_number)
        world = load_world(week.world)
        start = _moved(world.start, nudge)
        sub = load_submission(folder, week)
        if not sub.ok:
            raise RuntimeError(f"{folder}: {[str(e) for e in sub.errors]}")
        try:
            brain = LocalBrain(sub, week, start=start)
            sim = Simulator(world, brain, week.spec, dt=week.dt, start=start, signals=week_signals(week))
            return [sim.run(week.seconds)]
        finally:
            sub.unload()
    return run


def trusted_run(world_name: str, make_brain: Callable[[Any, tuple], Any], week_number: int,
                start: tuple[float, float, float], seconds: float, dt: float = 0.033,
                until_hit: bool = False) -> Scenario:
    def run() -> list[Trace]:
        spec = spec_for_week(week_number)
        sim = Simulator(load_world(world_name), make_brain(spec, start), spec, dt=dt, start=start)
        return [sim.run(seconds, stop_on_collision=until_hit)]
    return run


def fleet_run(world: World, robots: list[tuple[Any, tuple]], seconds: float, dt: float = 0.033) -> Scenario:
    def run() -> list[Trace]:
        spec = spec_for_week(4)
        fleet = Fleet(world, [(make(spec, start), spec, start) for make, start in robots], dt=dt)
        return fleet.run(seconds, stop_on_collision=False)
    return run


def cli_run(week_number: int) -> Callable[[], list[dict]]:
    """`simiam run weekN --solutions` as a user runs it; its trace JSON less `meta` (it names the folder)."""
    def run() -> list[dict]:
        with tempfile.TemporaryDirectory(prefix="step-identity-") as tmp:
            subprocess.run([sys.executable, "-m", "simiam.cli", "run", f"week{week_number}", "--solutions",
                            "--out", tmp], check=False, capture_output=True, cwd=ROOT)
            name = get_week(week_number).name
            data = json.loads((Path(tmp) / f"{name}.json").read_text())
        data.pop("meta", None)
        return [plain(data)]
    return run


def _avoid(spec: Any, start: tuple) -> Any:
    return instructor_tool("reference_brains").AvoidObstaclesBrain(spec, start=start)


def _goal(goal: tuple[float, float]) -> Callable[[Any, tuple], Any]:
    return lambda spec, start: instructor_tool("reference_brains").GoToGoalBrain(spec, goal, start=start,
                                                                                 ensure="week3")


def _constant(vel_r: float, vel_l: float) -> Callable[[Any, tuple], ConstantBrain]:
    return lambda spec, start: ConstantBrain(vel_r, vel_l)


def scenarios(quick: bool, tmp: Path) -> Iterator[tuple[str, Callable[[], list]]]:
    for n in range(1, 8):
        for label, nudge in NUDGES.items():
            yield f"solution/week{n}/{label}", course_run(ROOT / "solutions" / f"week{n}", n, nudge)
    rng = random.Random(24)
    for world_name, week_number in (("week4", 4), ("week5", 5), ("week6", 6), ("final", 7)):
        for k in range(10):  # the same draws with --quick (the same run under the same name), fewer runs
            start = (rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2), rng.uniform(-math.pi, math.pi))
            speeds = (rng.uniform(-6, 6), rng.uniform(-6, 6))
            if quick and k >= 4:
                continue
            yield f"avoid/{world_name}/{k}", trusted_run(world_name, _avoid, 4, start, 30.0)
            dt = 0.05 if week_number >= 6 else 0.033
            brain = _constant(*speeds)
            yield f"constant/{world_name}/{k}", trusted_run(world_name, brain, week_number, start, 12.0, dt)
    for k, goal in enumerate(((1.0, 1.0), (-1.0, 0.5), (0.3, -1.1))):
        yield f"goal/week3/{k}", trusted_run("week3", _goal(goal), 3, (0.0, 0.0, 0.0), 20.0, until_hit=True)
    two = [(_avoid, (0.0, 0.0, 0.0)), (_avoid, (0.3, 0.1, 2.0))]
    yield "fleet/week4", fleet_run(load_world("week4"), two, 30.0)
    yield "fleet/head_on", fleet_run(World("empty", []), [(_constant(6.0, 6.0), (0.0, 0.0, 0.0)),
                                                          (_constant(6.0, 6.0), (0.4, 0.0, math.pi))], 3.0)
    if quick:
        return
    for patch in sorted(WRONG.glob("*.patch")):
        week_number = int(patch.stem.removeprefix("good_").split("_")[0].removeprefix("week"))
        folder = apply_mistake(patch, ROOT / "solutions", tmp / patch.stem)[1]
        for label in ("start", "dx"):
            yield f"wrong/{patch.stem}/{label}", course_run(folder, week_number, NUDGES[label])
    for n in range(1, 8):
        yield f"cli/week{n}", cli_run(n)


def _first_difference(a: Any, b: Any, where: str = "") -> str | None:
    if type(a) is not type(b):
        return f"{where}: {a!r:.80} != {b!r:.80}"
    if isinstance(a, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return f"{where}.{key}: only in {'before' if key in a else 'after'}"
            found = _first_difference(a[key], b[key], f"{where}.{key}")
            if found:
                return found
        return None
    if isinstance(a, list):
        for i, (x, y) in enumerate(zip(a, b, strict=False)):
            found = _first_difference(x, y, f"{where}[{i}]")
            if found:
                return found
        return None if len(a) == len(b) else f"{where}: {len(a)} rows before, {len(b)} after"
    return None if a == b else f"{where}: {a!r} before, {b!r} after"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mode", choices=("record", "compare"))
    parser.add_argument("path", type=Path)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--only", default="", help="run only the scenarios whose name holds this text")
    args = parser.parse_args()
    exact_calls = [0]
    original = robot_surfaces.transform_exact

    def counted(*a: Any, **k: Any) -> Any:
        exact_calls[0] += 1
        return original(*a, **k)

    robot_surfaces.transform_exact = counted  # type: ignore[assignment]
    before = None
    if args.mode == "compare":
        with gzip.open(args.path, "rt") as f:
            before = json.load(f)
    out: dict[str, Any] = {}
    differ = []
    steps = 0
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="step-identity-") as tmp:
        for name, scenario in scenarios(args.quick, Path(tmp)):
            if args.only not in name:
                continue
            traces = scenario()
            rec = [t if isinstance(t, dict) else record_of(t) for t in traces]
            steps += sum(len(r["steps"]["t"]) for r in rec)
            out[name] = rec
            if before is not None:
                if name not in before:
                    differ.append(f"{name}: not in {args.path}")
                    continue
                found = _first_difference(before[name], rec, name)
                if found:
                    differ.append(found)
    print(f"{len(out)} scenarios, {steps} recorded steps, exact path ran {exact_calls[0]} times, "
          f"{time.perf_counter() - t0:.0f} s")
    if args.mode == "record":
        with gzip.open(args.path, "wt") as f:
            json.dump(out, f, separators=(",", ":"))
        print(f"recorded: {args.path}")
        return 0
    assert before is not None
    # a full recording compared --quick: the runs --quick leaves out are not missing
    missing = [] if args.quick else sorted(name for name in set(before) - set(out) if args.only in name)
    for line in differ + [f"{m}: recorded, not run now" for m in missing]:
        print(f"DIFFERS {line}")
    if differ or missing:
        return 1
    print("identical: every pose, reading, tick, collision and trace value, bit for bit")
    return 0


if __name__ == "__main__":
    sys.exit(main())
