"""A verdict the machine spoiled: a check during which a worker was held up past its wall bound is run again,
and where it cannot be, the result says "graded under load: regrade", never a timeout against the student.

A worker's wait passes its wall bound with the student's own time under its limit only when the machine
held the worker up (grader.sandbox.worker_clock: stopped, starved of CPU for `stall_seconds`); the session
then raises MachineStalled and records it in the grading's TimeBudget. The grading runs such a check again,
REDOS times at most (each try from a fresh worker). A check still stalled after that keeps no points and
status "error" with the UNDER_LOAD message; the result's `under_load` lists those checks, and a batch lists
such students for the instructor to grade again (grader.batch.runner). Nothing is charged for the stall.
"""

from __future__ import annotations

from collections.abc import Callable, MutableMapping
from typing import Any

from grader.result import CheckResult
from grader.sandbox.time_budget import TimeBudget

REDOS = 2  # a check the machine held up is run again at most this many times
UNDER_LOAD = "graded under load: regrade"
BLIND_NOTE = ("time limits were judged by the wall clock, three times the stated ones, because this system "
              "cannot tell the worker's CPU time: on a very busy machine a timeout may not be your code's")


def run_again_if_stalled(run: Callable[[], CheckResult], budget: TimeBudget, memo: MutableMapping[Any, Any],
                         keep: Callable[[Any], bool]) -> tuple[CheckResult, list[str]]:
    """`run()` a check; while a worker stalled during it, run it again (REDOS times at most). The result and
    what the stalls of its last try said (empty: the verdict stands).

    What a stalled try left in `memo` (the runs checks share, grader.checks.Context.memo) is dropped, but
    for the keys `keep` names (an open session): no later try, and no other check, reads a stalled run."""
    for _ in range(REDOS + 1):
        before, known = len(budget.stalls), set(memo)
        result = run()
        stalls = budget.stalls[before:]
        if not stalls:
            return result, []
        for key in [k for k in memo if k not in known and not keep(k)]:
            del memo[key]
    return spoiled(result, stalls), stalls


def spoiled(result: CheckResult, stalls: list[str]) -> CheckResult:
    """`result` as a check the machine kept from being graded: no verdict on the student's code."""
    result.status = "error"
    result.points = 0.0
    result.message = (f"{UNDER_LOAD}: the grading machine was too busy to give this check a verdict "
                      f"({stalls[-1]}), {REDOS + 1} times; this says nothing about your code, and the course "
                      f"staff will grade it again")
    result.details = {"under_load": stalls[-3:]}
    return result


def under_load_record(checks: list[str], stalls: list[str]) -> dict:
    """The result's `under_load`: which checks (or "load", the submission's import) got no verdict."""
    return {"regrade": True, "checks": checks, "message": f"{UNDER_LOAD}: {len(checks)} check(s) could not "
            f"be graded on this machine ({', '.join(checks[:6])}); grade this submission again",
            "stalls": stalls[-5:]}
