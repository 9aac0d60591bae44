"""Where the time of `grade weekN --solutions` goes: imports, splicing, worker start, round trips, the
property cases, the scenarios' physics, the report. The measurements behind docs/performance.md.

    python benchmarks/grade_profile.py [--week 3] [--sandbox auto|bwrap|subprocess]

Run it as a fresh process (it is the profile of a cold `grade`). It prints the machine line, then:
1. imports: `python -X importtime` of a fresh `grade weekN --solutions`, summed per top-level package;
2. one cold grade_submission in this process with timers around its phases (wall, and this process's CPU):
   splicing, worker start and load, probe and brain_step round trips (count and cost per call), property
   checks beyond their round trips (Hypothesis and the reference maths), scenarios beyond their round
   trips (physics, metrics), the JSON and HTML report, then a second, warm grading for comparison;
3. Hypothesis's own cost per case: a property with a no-op body run by Hypothesis with the grader's
   settings, against drawing the same inputs with `random` and calling the body directly.
Timers wrap functions from outside (nothing in the grader changes); they cost a few microseconds a call.
"""

from __future__ import annotations

import argparse
import collections
import functools
import json
import random
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
_CLI = "import sys; from grader.cli import main; sys.exit(main())"  # what the `grade` script runs

began_imports = time.perf_counter(), time.process_time()
import grader.cli  # noqa: E402, F401  (the imports a fresh `grade` pays before grading)
import grader.grading as grading  # noqa: E402
from grader.sandbox.session import RemoteBrain, StudentSession  # noqa: E402
from simiam.course.weeks import week_numbers  # noqa: E402
from simiam.machine import Stopwatch, descendants_cpu, load_after_line, machine_line, prepare_bytecode  # noqa: E402

IMPORT_WALL = time.perf_counter() - began_imports[0]
IMPORT_CPU = time.process_time() - began_imports[1]


# ---- 1. imports -------------------------------------------------------------------------------------
def import_breakdown(week: int, sandbox: str) -> tuple[float, list[tuple[str, float, int]]]:
    """(total seconds, [(top-level package, seconds of its own module bodies, modules)]) of the imports
    of a fresh `grade weekN --solutions`, from `python -X importtime` (self times, so nothing counts
    twice)."""
    with tempfile.TemporaryDirectory(prefix="simiam-profile-") as out:
        done = subprocess.run([sys.executable, "-X", "importtime", "-c", _CLI, f"week{week}", "--solutions",
                               "--out", out, "--sandbox", sandbox], capture_output=True, text=True)
    per: dict[str, list[float]] = collections.defaultdict(lambda: [0.0, 0])
    total = 0.0
    for line in done.stderr.splitlines():
        m = re.match(r"import time:\s+(\d+) \|\s+(\d+) \|(\s*)(\S+)", line)
        if not m:
            continue
        own = int(m.group(1)) / 1e6
        top = m.group(4).split(".")[0]
        per[top][0] += own
        per[top][1] += 1
        total += own
    rows = sorted(((k, v[0], int(v[1])) for k, v in per.items()), key=lambda r: -r[1])
    return total, rows


def _stdlib(name: str) -> bool:
    return name in sys.stdlib_module_names or name.startswith("_")


# ---- 2. phases of one grading -----------------------------------------------------------------------
class Timers:
    """Accumulated wall seconds, CPU seconds of the grading thread, CPU seconds of the live worker (where
    asked for: a /proc sweep costs about a millisecond) and call counts, per key."""

    def __init__(self) -> None:
        self.wall: dict[str, float] = collections.defaultdict(float)
        self.cpu: dict[str, float] = collections.defaultdict(float)
        self.worker: dict[str, float] = collections.defaultdict(float)
        self.count: dict[str, int] = collections.defaultdict(int)

    def wrap(self, fn, key, worker: bool = False):
        @functools.wraps(fn)
        def timed(*args, **kwargs):
            name = key(args, kwargs) if callable(key) else key
            w0 = descendants_cpu() if worker else 0.0
            t0, c0 = time.perf_counter(), time.thread_time()
            try:
                return fn(*args, **kwargs)
            finally:
                self.wall[name] += time.perf_counter() - t0
                self.cpu[name] += time.thread_time() - c0
                self.count[name] += 1
                if worker:
                    self.worker[name] += descendants_cpu() - w0
        return timed


def patch(owner, name: str, timers: Timers, key, worker: bool = False) -> None:
    """Wrap owner.name, and every module-level alias of the same function (`from x import f`)."""
    original = getattr(owner, name)
    wrapped = timers.wrap(original, key, worker)
    setattr(owner, name, wrapped)
    for module in list(sys.modules.values()):
        namespace = getattr(module, "__dict__", None)
        if namespace is None:
            continue
        for attr, value in list(namespace.items()):
            if value is original:
                setattr(module, attr, wrapped)


def instrument(week: int) -> Timers:
    import grader.properties as properties
    import grader.scenarios as scenarios
    from grader.checks import checks_for_week

    checks_for_week(week)  # import the week's checks so that their `from ... import` aliases get wrapped
    timers = Timers()
    patch(StudentSession, "load", timers, "worker start and load", worker=True)
    patch(StudentSession, "call", timers, lambda a, k: f"round trip: {a[1]}")
    patch(StudentSession, "probe_many", timers, "round trip: probe_many")
    many = StudentSession.probe_many

    def counted(self, probes, *args, **kwargs):  # how many probes went in the probe_many requests
        timers.count["probes in probe_many"] += len(probes)
        return many(self, probes, *args, **kwargs)

    StudentSession.probe_many = counted
    patch(RemoteBrain, "step", timers, "scenario steps (round trip + command check)")
    patch(grading, "_splice", timers, "splice (skeleton check included)")
    patch(grading, "write_outputs", timers, "report: JSON and HTML")
    patch(properties, "run_property", timers, "property checks (all)", worker=True)
    patch(scenarios, "run", timers, "scenario runs (all)", worker=True)
    patch(scenarios, "min_clearance", timers, "scenario metric: min_clearance (pure Python)")
    return timers


def grade_once(week: int, sandbox: str, out: Path) -> tuple[float, float, float, dict]:
    """(wall, CPU of this thread, CPU of the workers, result) of one grading."""
    c0 = time.thread_time()
    with Stopwatch() as sw:
        result = grading.grade_submission(week, ROOT / "solutions" / f"week{week}", seed=2014, out_dir=out,
                                          sandbox=sandbox)
    return sw.usage.wall, time.thread_time() - c0, sw.usage.cpu_children, result


def print_phases(timers: Timers, wall: float, cpu: float, worker_cpu: float) -> None:
    w, c, wk, n = timers.wall, timers.cpu, timers.worker, timers.count
    steps = "scenario steps (round trip + command check)"
    probes = sum(w[k] for k in ("round trip: probe", "round trip: probe_many") if k in w)
    probes_cpu = sum(c[k] for k in ("round trip: probe", "round trip: probe_many") if k in c)
    prop, scen = "property checks (all)", "scenario runs (all)"
    rows = [
        ("splice (skeleton check included)", w["splice (skeleton check included)"],
         c["splice (skeleton check included)"], None),
        ("worker start and load", w["worker start and load"], c["worker start and load"],
         wk["worker start and load"]),
        ("property checks", w[prop], c[prop], wk[prop]),
        ("  probe round trips", probes, probes_cpu, None),
        ("  the rest: drawing cases, reference maths", w[prop] - probes, c[prop] - probes_cpu, None),
        ("scenario runs", w[scen], c[scen], wk[scen]),
        ("  brain_step round trips", w[steps], c[steps], None),
        ("  the rest: physics, trace, metrics", w[scen] - w[steps], c[scen] - c[steps], None),
        ("  of which min_clearance (pure Python)", w["scenario metric: min_clearance (pure Python)"],
         c["scenario metric: min_clearance (pure Python)"], None),
        ("report: JSON and HTML", w["report: JSON and HTML"], c["report: JSON and HTML"], None),
    ]
    top = [r for r in rows if not r[0].startswith("  ")]
    rows.append(("the rest (other checks' code, scoring, glue)", wall - sum(r[1] for r in top),
                 cpu - sum(r[2] for r in top), None))
    rows.append(("total grade_submission", wall, cpu, worker_cpu))
    print(f"  {'':50s} {'wall ms':>8s} {'grader CPU ms':>14s} {'worker CPU ms':>14s}")
    for label, secs, cpus, work in rows:
        work_text = "" if work is None else f"{work * 1000:14.0f}"
        print(f"  {label:50s} {secs * 1000:8.0f} {cpus * 1000:14.0f} {work_text}")
    for key in sorted(k for k in w if k.startswith("round trip: ") and n[k]):
        extra = f" ({n['probes in probe_many']} probes)" if key.endswith("probe_many") else ""
        print(f"  {key:30s} {n[key]:5d} calls, {w[key] / n[key] * 1e6:6.0f} us wall, "
              f"{c[key] / n[key] * 1e6:6.0f} us grader CPU each{extra}")


# ---- 3. Hypothesis per case -------------------------------------------------------------------------
class InProcessSession:
    """Answers probes in this process from the trusted reference solution (grader.inside.worker_loop's
    own dispatcher, JSON in between): the property checks without round trips, for timing only."""

    def __init__(self, week: int, folder: Path) -> None:
        from grader.inside.worker_loop import _Worker

        self._worker = _Worker({"submission": str(folder), "week": week})

    def call(self, op: str, timeout: float | None = None, **fields):
        answer = self._worker.handle(json.loads(json.dumps({"id": 1, "op": op, **fields})))
        if not answer["ok"]:
            raise RuntimeError(answer["error"])
        return json.loads(json.dumps(answer["value"]))

    def probe_many(self, probes: list, timeout: float | None = None, budget: object = None) -> list:
        return [self.call("probe", **probe) for probe in probes]  # trusted solutions: no answer budget


def property_engine_cost(week: int) -> list[tuple[str, int, float, float]]:
    """Per property check of `week`: (id, cases, CPU seconds under run_property, CPU seconds of calling
    its case function directly on the same inputs), probes answered in this process."""
    import grader.properties as properties
    from grader.checks import Context, checks_for_week

    recorded: dict[str, tuple] = {}
    original = properties.run_property

    def recording(ctx, check_id, strategies, case, **kw):
        inputs: list[dict] = []

        def keep(ctx, **args):
            case(ctx, **args)  # a run that stops at a probe to be batched (NeedsProbe) is not kept
            inputs.append(dict(args))

        t0 = time.thread_time()
        outcome = original(ctx, check_id, strategies, keep, **kw)
        recorded[check_id] = (case, inputs, time.thread_time() - t0)
        return outcome

    for module in list(sys.modules.values()):  # every `from grader.properties import run_property`
        for attr, value in list(getattr(module, "__dict__", {}).items()):
            if value is original:
                setattr(module, attr, recording)
    ctx = Context(week=week, seed=2014, session=InProcessSession(week, ROOT / "solutions" / f"week{week}"))
    for check in checks_for_week(week):
        if check.kind == "property" and check.visibility == "visible":
            check.run(ctx)
    rows = []
    for check_id, (case, inputs, engine) in recorded.items():
        t0 = time.thread_time()
        for args in inputs:
            try:
                case(ctx, **args)
            except Exception:  # noqa: BLE001 - a stateful probe may answer differently the second time
                pass
        rows.append((check_id, len(inputs), engine, time.thread_time() - t0))
    return rows


def hypothesis_per_case(examples: int = 25, runs: int = 5) -> tuple[float, float]:
    """(CPU seconds per case under Hypothesis with the grader's settings, per case drawn with random and
    called directly), a no-op property of two floats, best of `runs`."""
    from hypothesis import HealthCheck, Phase, Verbosity, given, seed, settings
    from hypothesis import strategies as st

    def body(v: float, w: float) -> None:
        return None

    best_h = best_r = float("inf")
    for k in range(runs):
        runner = settings(max_examples=examples, deadline=None, database=None, derandomize=False,
                          suppress_health_check=list(HealthCheck), report_multiple_bugs=False,
                          print_blob=False, verbosity=Verbosity.quiet,
                          phases=(Phase.explicit, Phase.generate, Phase.shrink))(
            seed(k)(given(v=st.floats(-0.5, 0.5), w=st.floats(-5, 5))(body)))
        t0 = time.thread_time()
        runner()
        best_h = min(best_h, (time.thread_time() - t0) / examples)
        rng = random.Random(k)
        t0 = time.thread_time()
        for _ in range(examples):
            body(v=rng.uniform(-0.5, 0.5), w=rng.uniform(-5, 5))
        best_r = min(best_r, (time.thread_time() - t0) / examples)
    return best_h, best_r


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--week", type=int, default=3, choices=week_numbers())
    p.add_argument("--sandbox", default="auto", choices=["auto", "bwrap", "subprocess"])
    args = p.parse_args(argv)
    from grader.sandbox.bench import sandbox_description

    print(machine_line(sandbox_description(args.sandbox)), flush=True)
    print(prepare_bytecode(), flush=True)
    total, rows = import_breakdown(args.week, args.sandbox)
    print(f"1. imports of a fresh `grade week{args.week} --solutions` (python -X importtime, own time per "
          f"top-level package): {total:.2f} s in all")
    stdlib = sum(r[1] for r in rows if _stdlib(r[0]))
    for name, secs, modules in rows:
        if not _stdlib(name) and secs >= 0.005:
            print(f"  {name:20s} {secs * 1000:6.0f} ms  ({modules} modules)")
    print(f"  {'standard library':20s} {stdlib * 1000:6.0f} ms")
    print(f"2. phases of one grade_submission, week {args.week} (this process imported grader.cli and "
          f"grader.grading first: {IMPORT_WALL * 1000:.0f} ms wall, {IMPORT_CPU * 1000:.0f} ms CPU)")
    timers = instrument(args.week)
    with tempfile.TemporaryDirectory(prefix="simiam-profile-") as out:
        wall, cpu, worker, result = grade_once(args.week, args.sandbox, Path(out))
        print(f"  cold (first grading in this process; lazy imports and caches count), "
              f"score {result['score']:g}/{result['max_score']:g}:")
        print_phases(timers, wall, cpu, worker)
        timers = instrument(args.week)
        wall, cpu, worker, _ = grade_once(args.week, args.sandbox, Path(out))
        print("  warm (the same again in this process):")
        print_phases(timers, wall, cpu, worker)
    rows = property_engine_cost(args.week)
    cases = sum(r[1] for r in rows)
    engine, direct = sum(r[2] for r in rows), sum(r[3] for r in rows)
    print(f"3. the week's visible property checks with probes answered in this process (no round trips): "
          f"{len(rows)} checks, {cases} cases; under run_property {engine * 1000:.0f} ms CPU, the same cases "
          f"called directly {direct * 1000:.0f} ms CPU: drawing the cases costs "
          f"{(engine - direct) / max(1, cases) * 1e6:.0f} us per case")
    per_h, per_r = hypothesis_per_case()
    print(f"   Hypothesis per case (CPU), no-op property of two floats, 25 examples: {per_h * 1e6:.0f} us; "
          f"drawn with random and called directly: {per_r * 1e6:.1f} us")
    print(load_after_line())
    return 0


if __name__ == "__main__":
    sys.exit(main())
