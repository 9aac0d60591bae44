"""A property check's cases, run with their probes sent to the worker in a few requests.

Run one after the other, the 25 cases of a check cost 25 round trips (about 0.4 ms of wall time and
0.25 ms of CPU in both processes each, docs/performance.md). The inputs are all drawn before the first
case runs, so the probes can go together: each case is first run up to its first probe, which is
recorded instead of sent (`NeedsProbe` stops the case there); the recorded probes of all cases go in one
`probe_many` request, whose answers the worker streams back one by one (StudentSession.probe_many); then
the cases run again with their answers served from that batch. A case that needs a further probe (week 2's
linearity asks three) stops there again, and its next probe goes with the next batch. The answers are kept
until the cases are done, so what all the rounds keep together is bounded by one AnswerBudget
(grader.inside.answer_bounds): an answer beyond it is a BadValue of its case.

What the checks see is what the loop `for inputs in cases: case(ctx, **inputs)` gives: the first case
that fails in that order, with its exception, the same answers (the worker runs the same probes in the
same order for cases with one probe each), a timeout or a dead worker attributed to the probe it
happened in, and `ctx.last_probe` as that loop leaves it. Two things differ, and only for code that keeps
state between calls: the probes of the cases after the failing one have run too (they were sent before
the failing answer was known), and a case's second probe runs after the other cases' first ones. Every
probe builds its robot, supervisor and controller afresh from the loaded submission (grader/inside/
probes*.py), so only module-level state of the student's own code could see the difference; the
Hypothesis search that shrinks a failure runs its cases one by one, as before.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from grader.checks import Context, Mismatch
from grader.inside.answer_bounds import AnswerBudget
from grader.inside.protocol import encode_request
from grader.sandbox.errors import SandboxError


class NeedsProbe(BaseException):
    """Raised by `ctx.probe` in a case whose served answers are used up: the probe is sent with the next
    batch. A BaseException, so that no `except Exception` in a case's code can swallow it."""


class Served:
    """The probes one case asked for and the answers the batches brought it (values, or SandboxErrors
    to raise); Context.probe takes them in order while this case runs."""

    def __init__(self) -> None:
        self.asked: list[tuple[str, dict[str, Any]]] = []
        self.answers: list[Any] = []
        self.used = 0  # answers taken in the case's current run

    def start_run(self) -> None:
        self.used = 0

    def answer(self, name: str, args: dict[str, Any]) -> Any:
        k = self.used
        if k < len(self.asked) and self.asked[k] != (name, args) and not _same(self.asked[k], (name, args)):
            raise RuntimeError(f"a property case asked for probe {name!r} with other inputs when run again: "
                               "case functions must depend on their inputs and answers only")
        if k == len(self.asked):
            self.asked.append((name, args))
        if k == len(self.answers):
            raise NeedsProbe
        self.used += 1
        value = self.answers[k]
        if isinstance(value, SandboxError):
            raise value
        return _copy(value)  # a case run again (one with several probes) gets it as it came


def _same(asked: tuple[str, dict], again: tuple[str, dict]) -> bool:
    """The same request as sent: == says no to a NaN computed afresh in each run, the JSON says yes."""
    return encode_request({"probe": asked}) == encode_request({"probe": again})


def _copy(value: Any) -> Any:
    """A fresh copy of a JSON value (a case may change the lists it was given). Recursive: every answer
    is at most MAX_DEPTH deep (grader.inside.answer_bounds, checked where the runner reads it)."""
    if isinstance(value, list):
        return [_copy(v) for v in value]
    if isinstance(value, dict):
        return {k: _copy(v) for k, v in value.items()}
    return value


def run_cases(ctx: Context, case: Callable[..., None], cases: Sequence[dict[str, Any]],
              fresh: int = 0) -> tuple[int, BaseException] | None:
    """Run `case(ctx, **inputs)` on `cases` in order until one raises Mismatch or a SandboxError: (its
    index, the exception), or None when all pass. Any other exception of the first case that raises
    propagates, as from the plain loop. The first `fresh` cases start with `ctx.last_probe = None` (the
    fixed examples do, grader.properties._one)."""
    served = [Served() for _ in cases]
    budget = AnswerBudget()  # every round's answers are kept until the cases are done: one budget for all
    passed = [False] * len(cases)
    first_open = 0  # every case before it has passed
    try:
        while True:
            waiting: list[int] = []  # cases stopped at a probe, in order
            for i in range(first_open, len(cases)):
                if passed[i]:  # passed in an earlier round, while a case before it waited
                    if first_open == i:
                        first_open += 1
                    continue
                served[i].start_run()
                ctx.serving = served[i]
                try:
                    case(ctx, **cases[i])
                except NeedsProbe:
                    waiting.append(i)
                    continue
                except Exception as exc:
                    if not waiting:  # every case before it passed: this is the loop's first failure
                        if isinstance(exc, (Mismatch, SandboxError)):
                            return i, exc
                        raise
                    break  # it or a case before it fails first: the cases after it do not matter
                finally:
                    ctx.serving = None
                passed[i] = True
                if first_open == i:
                    first_open += 1
            if not waiting:
                return None
            requests = [served[i].asked[len(served[i].answers)] for i in waiting]
            answers = ctx.session.probe_many([{"name": name, "args": args} for name, args in requests],
                                             timeout=ctx.call_seconds, budget=budget)
            if not answers:
                raise RuntimeError("probe_many answered nothing")
            for i, answer in zip(waiting, answers, strict=False):  # fewer answers after a timeout
                served[i].answers.append(answer)
    finally:
        ctx.serving = None
        ctx.last_probe = _last_probe(served, passed, fresh)


def _last_probe(served: list[Served], passed: list[bool], fresh: int) -> tuple[str, dict] | None:
    """`ctx.last_probe` as the plain loop leaves it: the last probe asked up to the case it stopped at."""
    last = None
    for i, one in enumerate(served):
        if i < fresh:
            last = None
        if one.used:
            last = one.asked[one.used - 1]
        if not passed[i]:
            break
    return last
