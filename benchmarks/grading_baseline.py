"""The baseline every grading benchmark measures in its own run, to divide its figures by.

Grading one submission cannot cost less than starting Python with the grader's imports
(`python -c 'import grader.grading'` in a fresh process) plus starting one bare sandboxed worker (the
sandbox and its trusted preloads, on an empty submission, no student code). Both are measured here, wall
and CPU seconds in all processes, median of a few runs; `grade week3` divided by their sum is the figure
that stays comparable between machines of different speed and under load.
"""

from __future__ import annotations

import subprocess
import sys
from dataclasses import dataclass

from grader.sandbox.bench import bare_worker_start, interpreter_start, sandbox_description
from simiam.machine import Stopwatch, Usage, median_usage


@dataclass
class Baseline:
    """The parts of grading that no submission can avoid, measured on this machine now."""

    python: Usage    # python -c pass
    imports: Usage   # python -c 'import grader.grading' (interpreter start included)
    worker: Usage    # a bare worker: started, loading an empty folder, closed
    sandbox: str     # the isolation used, in words

    @property
    def total(self) -> Usage:
        """Imports and a bare worker: the floor of grading one submission from the command line."""
        return _floor(self.imports, self.worker)

    def lines(self) -> list[str]:
        """The baseline as printed lines (milliseconds, wall and CPU)."""
        def ms(u: Usage) -> str:
            return f"{u.wall * 1000:5.0f} ms wall, {u.cpu * 1000:5.0f} ms CPU"
        return [f"baseline: interpreter start {ms(self.python)}",
                f"baseline: python -c 'import grader.grading' {ms(self.imports)}",
                f"baseline: bare worker start ({self.sandbox}) {ms(self.worker)}",
                f"baseline: imports + bare worker = {ms(self.total)}  (the ratios below divide by this)"]


def import_start(runs: int = 5) -> Usage:
    """Median of `python -c 'import grader.grading'` in a fresh process, wall and CPU."""
    usages = []
    for _ in range(runs):
        with Stopwatch() as sw:
            subprocess.run([sys.executable, "-c", "import grader.grading"], check=True)
        usages.append(sw.usage)
    return median_usage(usages)


def measure_baseline(sandbox: str = "auto", week: int = 3, runs: int = 5) -> Baseline:
    """Measure the baseline now (a few seconds)."""
    worker = median_usage([bare_worker_start(week, sandbox) for _ in range(runs)])
    return Baseline(interpreter_start(runs), import_start(runs), worker, sandbox_description(sandbox))


def paired(sandbox: str = "auto", week: int = 3) -> Usage:
    """One measurement of the baseline's total (an import start and a bare worker, once each), to take just
    before one run: a machine whose speed drifts within a benchmark divides each run by what it was then."""
    return _floor(import_start(1), bare_worker_start(week, sandbox))


def _floor(imports: Usage, worker: Usage) -> Usage:
    """The baseline's total: the imports and the bare worker, added."""
    return Usage(imports.wall + worker.wall, imports.cpu_self + worker.cpu_self,
                 imports.cpu_children + worker.cpu_children)


def pooled(before: Baseline, after: Baseline) -> Baseline:
    """One baseline from two measured around a benchmark's runs: each part the mean of the two medians,
    so that a machine whose speed drifted during the runs is divided by what it was on average."""
    def mean(a: Usage, b: Usage) -> Usage:
        return Usage((a.wall + b.wall) / 2, (a.cpu_self + b.cpu_self) / 2,
                     (a.cpu_children + b.cpu_children) / 2)

    return Baseline(mean(before.python, after.python), mean(before.imports, after.imports),
                    mean(before.worker, after.worker), before.sandbox)


def drift_line(before: Baseline, after: Baseline) -> str:
    """The baseline before and after the runs, and a warning where the machine's speed changed between."""
    b, a = before.total.cpu, after.total.cpu
    line = (f"baseline CPU before the runs {b * 1000:.0f} ms, after {a * 1000:.0f} ms: the ratios divide by "
            f"their mean")
    if min(a, b) > 0 and max(a, b) / min(a, b) > 1.15:
        line += " (the machine's speed changed by more than 15 % during the runs: run again to compare)"
    return line
