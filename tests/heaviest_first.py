"""The order in which pytest-xdist hands test modules to its two workers: the heaviest first.

`--dist loadscope` keeps a module on one worker (its module fixtures build once) and by default hands the
modules out by their number of tests, most first. The modules of one or two long tests (`grade selfcheck`
of every week under another kernel, the verdict matrix, week 7's hidden goals, the wheel) were handed out
last, where one of them can keep a worker busy long after the other has nothing left to take. Handing
out the module with the most expected seconds first (longest processing time first, the classic rule for
two machines) leaves only short modules for the end, whichever worker they land on.

SECONDS holds the modules expected to take more than a few seconds on an idle machine (from the suite's
`--durations` and each module's CPU seconds, test process and children, run alone with `-n 0`); any other
module counts PER_TEST seconds per test. Only the order follows from these figures: a stale one never
changes what a test proves, and only ratios matter, so figures taken under load serve as well. To
refresh the table after modules grew or shrank by much:

    python -m pytest -n 0 -q --durations=0 > durations.txt; python tests/heaviest_first.py durations.txt
"""

from __future__ import annotations

import re
import sys
from collections import defaultdict
from pathlib import Path

from xdist.scheduler import LoadScopeScheduling
from xdist.workermanage import WorkerController

# Modules sharing a session fixture that takes long to build, kept on one worker so that it is built once:
# the week-3 Gradescope bundle (`grade package`, a wheel build) and the venv its setup.sh installs
# (tests/platforms/conftest.py: gradescope_zip, autograder), some 25 s per worker that builds them.
TOGETHER = {module: "tests/platforms: the Gradescope bundle and its venv" for module in (
    "tests/platforms/test_coursera.py", "tests/platforms/test_gradescope_bundle.py",
    "tests/platforms/test_platform_layout.py", "tests/platforms/test_prairielearn.py")}
PER_TEST = 0.15  # s: the typical test of a module not in SECONDS
SHOWN = 3.0  # s: a module is listed in SECONDS from this many seconds on

# module: expected seconds (see the module doc for how they were measured)
SECONDS: dict[str, float] = {
    "tests/docs/test_documented_commands.py": 90.0,
    "tests/platforms/test_platform_layout.py": 80.0,
    "tests/grader/test_checks_fail.py": 75.0,
    "tests/platforms/test_selfcheck_other_kernel.py": 70.0,
    "tests/grader/test_verdict_margins.py": 65.0,
    "tests/batch/test_batch_trust.py": 60.0,
    "tests/grader/test_hidden_week7.py": 60.0,
    "tests/packaging/test_wheel.py": 50.0,
    "tests/grader/test_under_load.py": 45.0,
    "tests/platforms/test_coursera.py": 45.0,
    "tests/fidelity/test_pinned_fidelity.py": 36.0,
    "tests/batch/test_batch_hostile.py": 30.0,
    "tests/grader/test_same_after_issue24.py": 30.0,
    "tests/batch/test_batch_overlap.py": 25.0,
    "tests/platforms/test_selfcheck.py": 25.0,
    "tests/sandbox/test_windows_like.py": 25.0,
    "tests/sandbox/test_attacks.py": 20.0,
    "tests/platforms/test_prairielearn.py": 20.0,
    "tests/sandbox/test_answer_bounds.py": 18.0,
    "tests/sandbox/test_stuck.py": 15.0,
    "tests/platforms/test_bundle.py": 15.0,
    "tests/batch/test_batch_dask.py": 14.0,
    "tests/sandbox/test_attacks_graded.py": 12.0,
    "tests/batch/test_hostile_pages.py": 12.0,
    "tests/grader/test_tracking_goals.py": 10.0,
    "tests/grader/test_hidden_week6.py": 10.0,
    "tests/platforms/test_gradescope_bundle.py": 10.0,
    "tests/fidelity/test_week7_reference.py": 10.0,
    "tests/sandbox/test_worker_clock.py": 10.0,
    "tests/grader/test_hidden.py": 9.0,
    "tests/simulator/test_physics_pass.py": 8.0,
    "tests/batch/test_batch_grades_back_e2e.py": 8.0,
    "tests/grader/test_probe_batching.py": 7.0,
    "tests/batch/test_batch_runner.py": 7.0,
}


def expected_seconds(scope: str, tests: int) -> float:
    """What a module (or a group of TOGETHER: its members' figures added) is expected to cost: its measured
    seconds, and at least PER_TEST per test."""
    members = [module for module, group in TOGETHER.items() if group == scope] or [scope]
    return max(sum(SECONDS.get(module, 0.0) for module in members), PER_TEST * tests)


class HeaviestFirst(LoadScopeScheduling):
    """LoadScopeScheduling handing out the module with the most expected seconds left in the queue, the
    modules of TOGETHER as one."""

    def _split_scope(self, nodeid: str) -> str:
        scope = super()._split_scope(nodeid)
        return TOGETHER.get(scope.split("::")[0], scope)

    def _assign_work_unit(self, node: WorkerController) -> None:
        heaviest = max(self.workqueue, key=lambda scope: expected_seconds(scope, len(self.workqueue[scope])))
        self.workqueue.move_to_end(heaviest, last=False)  # the base class hands out the first
        super()._assign_work_unit(node)


def table(durations: str) -> dict[str, float]:
    """{module: seconds} from the `--durations=0` lines of a pytest run, modules of at least SHOWN s."""
    total: dict[str, float] = defaultdict(float)
    for line in durations.splitlines():
        found = re.match(r"\s*([\d.]+)s (?:setup|call|teardown)\s+(\S+?\.py)(?:::|\s*$)", line)
        if found:
            total[found[2]] += float(found[1])
    return {module: round(s, 1) for module, s in sorted(total.items(), key=lambda kv: -kv[1]) if s >= SHOWN}


if __name__ == "__main__":
    measured = table(Path(sys.argv[1]).read_text())
    print("SECONDS: dict[str, float] = {")
    for module, seconds in measured.items():
        print(f'    "{module}": {seconds},')
    print("}")
