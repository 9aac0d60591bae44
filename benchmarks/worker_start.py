"""Where the CPU of one bubblewrap worker start goes, piece by piece, counted exactly.

    sudo python benchmarks/worker_start.py [--runs 25] [--week 3]

Every piece runs as a child placed in a cpuacct cgroup (cgroup v1, as root), so the CPU of every
process it starts is counted, bubblewrap's and the sandboxed ones included: they are never waited for
along the chain, which is why `python -m grader.sandbox.bench` has to sample /proc instead and may miss
up to 20 ms per process. Pieces, each with the worker's own bubblewrap arguments (plan_worker for the
week's solution): bubblewrap running /bin/true; the interpreter (`python -I -S -B -c pass`) inside it;
`import numpy` inside it; the worker's preloads inside it (with the shared library of
grader.sandbox.library), then whole sessions started in a fresh process: imports only, a bare worker
(empty folder) and the week's solution loaded. Medians of `--runs`, alternating, with the machine line.
`--compare TREE` runs the fresh-process pieces of another checkout too (PYTHONPATH=TREE, e.g. main
unpacked with `git archive`), alternating with this one in every round: before and after under the same
load.
"""

from __future__ import annotations

import argparse
import os
import signal
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from grader.sandbox import isolation
from grader.sandbox.limits import Limits
from simiam.machine import load_after_line, machine_line

ROOT = Path(__file__).resolve().parents[1]
CGROUP = Path("/sys/fs/cgroup/cpuacct") / f"simiam-worker-start-{os.getpid()}"
PRELOADS = ("math", "faulthandler", "resource", "numpy", "simiam.control", "simiam.course.weeks",
            "simiam.course.loader", "grader.inside.rlimits", "grader.inside.seccomp",
            "grader.inside.worker_loop", "ctypes", "grader.inside.probes")
SESSION = ("import sys, tempfile; from pathlib import Path; import grader.grading\n"
           "from grader.sandbox.session import StudentSession\n"
           "folder = sys.argv[1] or tempfile.mkdtemp()\n"
           "with StudentSession(int(sys.argv[2]), Path(folder), sandbox='bwrap') as s: s.load()\n")


def _join() -> None:
    (CGROUP / "cgroup.procs").write_text(str(os.getpid()))


def _cpu() -> float:
    return int((CGROUP / "cpuacct.usage").read_text()) / 1e9


def pieces(week: int) -> dict[str, list[str]]:
    """The commands to measure, by name."""
    limits = Limits()
    if hasattr(isolation, "worker_library"):
        library = isolation.worker_library(isolation.BWRAP, Path())
    else:  # a tree from before the shared library (to measure "before" with PYTHONPATH=that tree)
        from grader.sandbox.exposed import build_library

        library = build_library(Path(tempfile.mkdtemp(prefix="simiam-bench-library-")) / "library")
    folder = ROOT / "solutions" / f"week{week}"
    plan = isolation.plan_worker(isolation.BWRAP, folder, {"week": week, "rlimits": None},
                                 tmp_bytes=limits.tmp_bytes, library=library)
    sandbox = plan.argv[:plan.argv.index("--")]
    python = [sys.executable, "-I", "-S", "-B", "-c"]
    paths = f"import sys; sys.path[:] = [p for p in sys.path if p] + {plan.config['paths']!r}\n"
    preload = paths + "".join(f"import {name}\n" for name in PRELOADS)
    preload += f"simiam.course.weeks.get_week({week})\n"
    return {
        "bubblewrap -- /bin/true": [*sandbox, "--", "/bin/true"],
        "bubblewrap -- python -I -S -B -c pass": [*sandbox, "--", *python, "pass"],
        "bubblewrap -- python: import numpy": [*sandbox, "--", *python, paths + "import numpy"],
        "bubblewrap -- python: the worker's preloads": [*sandbox, "--", *python, preload],
    }


def fresh_pieces(week: int, label: str = "") -> dict[str, list[str]]:
    """Whole sessions, each in a fresh grading process (imports, worker start, load, close)."""
    session = [sys.executable, "-c", SESSION]
    folder = ROOT / "solutions" / f"week{week}"
    name = f"fresh process{label}"
    return {f"{name}: import grader.grading": [sys.executable, "-c", "import grader.grading"],
            f"{name}: imports + a bare worker": [*session, "", str(week)],
            f"{name}: imports + week {week} solution loaded": [*session, str(folder), str(week)]}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=25)
    parser.add_argument("--week", type=int, default=3)
    parser.add_argument("--compare", metavar="TREE", help="another checkout, measured alternately")
    args = parser.parse_args(argv)
    if not isolation.bwrap_works()[0]:
        raise SystemExit("bubblewrap is not usable here: " + isolation.bwrap_works()[1])
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # so that the cgroup is removed (finally)
    try:
        CGROUP.mkdir()
    except OSError as exc:
        raise SystemExit(f"cannot make a cpuacct cgroup ({exc}): this benchmark needs root and cgroup v1's "
                         "cpuacct; use `python -m grader.sandbox.bench` instead") from None
    try:
        print(machine_line("bubblewrap"), flush=True)
        commands = {**pieces(args.week), **fresh_pieces(args.week)}
        envs: dict[str, dict | None] = {name: None for name in commands}
        if args.compare:
            other = fresh_pieces(args.week, f" ({args.compare})")
            commands.update(other)
            envs.update({name: dict(os.environ, PYTHONPATH=args.compare) for name in other})
        runs: dict[str, list[float]] = {name: [] for name in commands}
        for _ in range(args.runs):
            for name, command in commands.items():
                before = _cpu()
                subprocess.run(command, cwd=tempfile.gettempdir(), env=envs[name], check=True,
                               preexec_fn=_join, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                runs[name].append(_cpu() - before)
        for name, cpu in runs.items():
            print(f"{name:52} {statistics.median(cpu) * 1000:7.1f} ms CPU median, {min(cpu) * 1000:7.1f} min")
        print(load_after_line())
    finally:
        CGROUP.rmdir()


if __name__ == "__main__":
    main()
