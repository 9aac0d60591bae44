"""CPU per simulated step of a scenario run, both processes: the sandboxed step against the ideal
two-process step and the one-process step, all in one run (issue 32).

    python benchmarks/step_bench.py [--weeks 3 4 6] [--repeat 5] [--sandbox auto|bwrap|subprocess]
                                    [--against DIR]

Each week's line also splits the step and the ideal by process (the grader's thread and the worker, the
ideal's parent and child) and says how far each side is above the ideal's.

Per week, the week's solutions run the week's `simiam run` scenario (its world, start, settings and length),
and each figure is the CPU of every process taking part, read from /proc/*/schedstat (nanoseconds on a
CPU) over steps 2..N of the run (the first step starts the brain), divided by the steps; best of `--repeat`:
- step: the grader's real step, RemoteBrain over a StudentSession (the sandboxed worker), as grading runs
  it (grader thread and worker pinned to one core, grader.sandbox.same_core);
- ideal: a fresh-interpreter child runs the real brain (LocalBrain) on the same readings, the parent the
  real trusted step (the Simulator with the recorded answers, validation and record), one byte each way
  on a pipe, both on one core: what any two-process design costs at least;
- record floor: as the ideal, but the readings go as their record and the child unpacks them into the
  dict the brain reads, and answers with the two wheel speeds in a record as long as the solution's real
  answer records (the parent unpacks the speeds): what any design of step records costs at least, before
  the rest of the answer is packed, checked and read;
- one process: the Simulator with LocalBrain in this thread.
`--against DIR` also measures the step of another checkout (e.g. `git archive BASE | tar -x -C DIR`),
alternating with this one, so that an A/B holds under the same load; with `--repeat` 4 or more it also
prints the lower quartile of each side's runs and their ratio. The load is printed before and
after: on a shared machine compare the ratios of one run, not runs of other days.
"""

from __future__ import annotations

import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

import simiam  # noqa: F401  (before numpy: it pins the BLAS kernel)
from grader.inside.step_record import StepLayout, layout_for
from grader.sandbox.same_core import SameCore
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.machine import load_after_line, machine_line
from simiam.signals import week_signals
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[1]

# The child of the ideal step and of the record floor: the real brain.
# ideal: on the recorded readings, one byte in, one byte out;
# floor: on the readings record the parent sends (unpacked into the dict the brain reads), answering with
# its two wheel speeds packed in a record as long as the solution's answer records.
_CHILD = """
import json, os, struct, sys
import simiam
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
week_n, folder, readings_file, cpu = int(sys.argv[1]), sys.argv[2], sys.argv[3], int(sys.argv[4])
mode, size = sys.argv[5], int(sys.argv[6])
if cpu >= 0:
    os.sched_setaffinity(0, {cpu})
week = get_week(week_n)
readings = json.load(open(readings_file))
brain = LocalBrain(load_submission(folder, week), week, start=None)
os.write(1, b"r")
if mode == "ideal":
    for r in readings:
        if os.read(0, 1) != b"s":
            break
        brain.step(r)
        os.write(1, b"a")
else:
    from grader.inside.step_record import HEADER, layout_for
    from simiam.signals import week_signals
    unpack = layout_for(week_signals(week), len(week.spec.ir_mounts)).readings.unpack_from
    pack, pad = struct.Struct("<2d").pack, bytes(size - 16)
    while data := os.read(0, 65536):
        t, dt, right, left, *ir_raw = unpack(data, HEADER.size)
        answer = brain.step({"t": t, "dt": dt, "ticks": [right, left], "ir_raw": ir_raw})
        os.write(1, pack(answer["vel_r"], answer["vel_l"]) + pad)
"""


def schedstat_ns(pid: int | str) -> int:
    """Nanoseconds on a CPU of every thread of process `pid` ("thread-self": this thread only)."""
    if pid == "thread-self":
        paths = ["/proc/thread-self/schedstat"]
    else:
        paths = [f"/proc/{pid}/task/{t}/schedstat" for t in os.listdir(f"/proc/{pid}/task")]
    total = 0
    for path in paths:
        with open(path) as f:
            total += int(f.read().split()[0])
    return total


class Recorder:
    """LocalBrain, keeping each step's readings and answer (the ideal step replays both)."""

    def __init__(self, brain: LocalBrain) -> None:
        self.brain, self.readings, self.answers = brain, [], []

    def step(self, readings: dict) -> Any:
        self.readings.append({k: list(v) if isinstance(v, list) else v for k, v in readings.items()})
        answer = self.brain.step(readings)
        self.answers.append(answer)
        return answer


class FloorBrain:
    """The parent's side of the record floor: the readings as their record, the answer's speeds unpacked
    from the child's record; the recorded answer (the rest of the answer is not decoded: a floor)."""

    def __init__(self, answers: list[Any], to_child: int, from_child: int, layout: StepLayout) -> None:
        self.answers, self.k, self.w, self.r, self.layout = answers, -1, to_child, from_child, layout
        self.speeds = struct.Struct("<2d").unpack_from

    def step(self, readings: dict) -> Any:
        self.k += 1
        os.write(self.w, self.layout.encode_readings(self.k, readings))  # type: ignore[arg-type]
        vel_r, vel_l = self.speeds(os.read(self.r, 65536))
        answer = self.answers[self.k]
        if (vel_r, vel_l) != (answer["vel_r"], answer["vel_l"]):
            raise SystemExit("the record floor's child answered other speeds than the recorded run")
        return answer


class OneByteBrain:
    """The parent's side of the ideal step: one byte to the child, one byte back, the recorded answer."""

    def __init__(self, answers: list[Any], to_child: int, from_child: int) -> None:
        self.answers, self.k, self.w, self.r = answers, -1, to_child, from_child

    def step(self, readings: dict) -> Any:
        os.write(self.w, b"s")
        os.read(self.r, 1)
        self.k += 1
        return self.answers[self.k]


def _simulator(week_n: int, brain: Any) -> tuple[Simulator, int]:
    week = get_week(week_n)
    world = load_world(week.world)
    sim = Simulator(world, brain, week.spec, dt=week.dt, start=world.start, signals=week_signals(week))
    return sim, int(round(week.seconds / week.dt))


def _steps(sim: Simulator, n: int, pids: list[int | str]) -> list[float]:
    """us of CPU per step of each of `pids` over steps 2..n."""
    sim.step()
    before = [schedstat_ns(p) for p in pids]
    for _ in range(n - 1):
        sim.step()
    return [(schedstat_ns(p) - b) / (n - 1) / 1000 for p, b in zip(pids, before, strict=True)]


def record(week_n: int, folder: Path) -> Recorder:
    """One run's readings and answers (untimed)."""
    week = get_week(week_n)
    sub = load_submission(folder, week)
    recorder = Recorder(LocalBrain(sub, week))
    sim, n = _simulator(week_n, recorder)
    for _ in range(n):
        sim.step()
    sub.unload()
    return recorder


def one_process(week_n: int, folder: Path) -> float:
    week = get_week(week_n)
    sub = load_submission(folder, week)
    sim, n = _simulator(week_n, LocalBrain(sub, week))
    us = _steps(sim, n, ["thread-self"])[0]
    sub.unload()
    return us


def ideal(week_n: int, folder: Path, recorder: Recorder, floor: bool = False) -> list[float]:
    """[the parent's, the child's] us of CPU per step: the ideal step, or with `floor` the record floor
    (the readings as a record each way, the answer's two speeds back in a record as long as the real
    ones: what any design of records must do at least)."""
    week = get_week(week_n)
    layout = layout_for(week_signals(week), len(week.spec.ir_mounts))
    size = len(layout.encode_answer(0, recorder.answers[0]) or b"")
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(recorder.readings, f)
    try:
        with SameCore() as cpu:
            child = subprocess.Popen([sys.executable, "-c", _CHILD, str(week_n), str(folder), f.name,
                                      str(-1 if cpu is None else cpu), "floor" if floor else "ideal",
                                      str(size)],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE)
            assert child.stdin is not None and child.stdout is not None
            to_child, from_child = child.stdin.fileno(), child.stdout.fileno()
            if os.read(from_child, 1) != b"r":
                raise SystemExit("the ideal step's child did not start")
            brain = FloorBrain(recorder.answers, to_child, from_child, layout) if floor \
                else OneByteBrain(recorder.answers, to_child, from_child)
            sim, n = _simulator(week_n, brain)
            us = _steps(sim, min(n, len(recorder.answers)), ["thread-self", child.pid])
            child.stdin.close()
            child.wait()
    finally:
        os.unlink(f.name)
    return us


def channel_step(week_n: int, folder: Path, sandbox: str) -> list[float]:
    """The grader's real step (RemoteBrain over a sandboxed worker): [grader thread's, worker's] us of CPU
    per step."""
    from grader.sandbox.session import RemoteBrain, StudentSession

    with StudentSession(week_n, folder, sandbox=sandbox) as session, SameCore() as cpu:
        session.load()
        sim, n = _simulator(week_n, RemoteBrain(session, None, cpu=cpu))
        sim.step()  # brain_start, then the worker's pid is known
        pid = session._worker.host_pid  # noqa: SLF001 - the benchmark reads the worker's own CPU
        return _steps(sim, n - 1, ["thread-self", pid])


def _against(directory: Path, week_n: int, sandbox: str) -> float:
    """channel_step run in another checkout (its grader and simiam), this script's code."""
    env = dict(os.environ, PYTHONPATH=str(directory))
    code = (f"import runpy; m = runpy.run_path({str(Path(__file__))!r}); "
            f"print(m['channel_step']({week_n}, m['ROOT'] / 'solutions' / 'week{week_n}', {sandbox!r}))")
    done = subprocess.run([sys.executable, "-c", code], env=env, cwd=directory, capture_output=True,
                          text=True, check=True)
    said = done.stdout.strip().splitlines()[-1]  # a checkout before the split prints the sum only
    return sum(json.loads(said)) if said.startswith("[") else float(said)


def _quartile(values: list[float]) -> float:
    """The lower quartile of `values` (at least one)."""
    return sorted(values)[len(values) // 4]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--weeks", type=int, nargs="+", default=[3, 4, 6])
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--sandbox", default="auto", choices=["auto", "bwrap", "subprocess"])
    p.add_argument("--against", type=Path, help="another checkout whose step is measured alternately")
    args = p.parse_args(argv)
    print(machine_line(args.sandbox), flush=True)
    for week_n in args.weeks:
        folder = ROOT / "solutions" / f"week{week_n}"
        recorder = record(week_n, folder)
        one = min(one_process(week_n, folder) for _ in range(args.repeat))
        ideals, floors, steps, others = [], [], [], []
        for _ in range(args.repeat):  # alternating, so that each sees the same load
            ideals.append(ideal(week_n, folder, recorder))
            floors.append(ideal(week_n, folder, recorder, floor=True))
            steps.append(channel_step(week_n, folder, args.sandbox))
            if args.against:
                others.append(_against(args.against, week_n, args.sandbox))
        (parent, child), (grader, worker) = min(ideals, key=sum), min(steps, key=sum)
        best_ideal, best_step, floor = parent + child, grader + worker, min(map(sum, floors))
        line = (f"week{week_n} ({len(recorder.answers)} steps): step {best_step:.1f} us "
                f"= {best_step / best_ideal:.2f}x ideal, {best_step / one:.1f}x one process; "
                f"ideal two-process {best_ideal:.1f} us = {best_ideal / one:.1f}x one process; "
                f"record floor {floor:.1f} us = {floor / best_ideal:.2f}x ideal; "
                f"one process {one:.1f} us (best of {args.repeat}; CPU of both processes per step); "
                f"split: step grader {grader:.1f} + worker {worker:.1f}, ideal parent {parent:.1f} + child "
                f"{child:.1f} (above the ideal: grader {grader - parent:+.1f}, worker {worker - child:+.1f})")
        if others:
            line += (f"; {args.against} step {min(others):.1f} us = {min(others) / best_ideal:.2f}x ideal "
                     f"(this step {best_step / min(others):.2f}x it")
            if args.repeat >= 4:  # on a machine whose speed drifts, a quartile of many says more than a best
                mine, theirs = _quartile([sum(s) for s in steps]), _quartile(others)
                line += f"; lower quartiles {mine:.1f} and {theirs:.1f} us: {mine / theirs:.2f}x"
            line += ")"
        print(line, flush=True)
    print(load_after_line())
    return 0


if __name__ == "__main__":
    sys.exit(main())
