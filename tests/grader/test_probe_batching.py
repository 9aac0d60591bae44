"""A property check's probes go to the worker in batches (grader/batched_cases.py), and what the check
sees is what the plain loop, one round trip per probe, gives: the same failing case and exception, the
same answers, timeouts and dead workers attributed to their own case, and the same `ctx.last_probe`."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest
from wrong_submissions import build, week_of

from grader import properties
from grader.batched_cases import run_cases
from grader.checks import Context, Mismatch
from grader.domains import Floats
from grader.grading import grade_submission
from grader.properties import run_property
from grader.sandbox.errors import SandboxError, StudentError, StudentTimeout, WorkerDied


def one_by_one(ctx: Context, case, cases, fresh: int = 0):
    """The plain loop that run_cases stands for (what properties.py ran before the batching)."""
    for i, inputs in enumerate(cases):
        if i < fresh:
            ctx.last_probe = None
        try:
            case(ctx, **inputs)
        except (Mismatch, SandboxError) as exc:
            return i, exc
    return None


class FakeSession:
    """Answers probes with `answer(name, args)` (a value, or a SandboxError raised) and keeps every
    request: one list of probes per `probe_many`, a one-item list per `call`. A timeout or dead worker
    ends a batch, as StudentSession.probe_many does."""

    def __init__(self, answer) -> None:
        self.answer = answer
        self.requests: list[list[tuple[str, dict]]] = []

    def _one(self, name: str, args: dict) -> Any:
        return self.answer(name, dict(args))

    def call(self, op: str, timeout: float | None = None, **fields: Any) -> Any:
        self.requests.append([(fields["name"], fields["args"])])
        return self._one(fields["name"], fields["args"])

    def probe_many(self, probes: list[dict], timeout: float | None = None, budget: Any = None) -> list[Any]:
        self.requests.append([(p["name"], p["args"]) for p in probes])
        out: list[Any] = []
        for p in probes:
            try:
                out.append(self._one(p["name"], p["args"]))
            except (StudentTimeout, WorkerDied) as exc:
                return [*out, exc]
            except SandboxError as exc:
                out.append(exc)
        return out

    @property
    def probes(self) -> list[tuple[str, dict]]:
        return [p for request in self.requests for p in request]


def _double(name: str, args: dict) -> Any:
    return [2 * args["x"]]


def _check_double(ctx: Context, x: float) -> None:
    got = ctx.probe("double", x=x)
    if got != [2 * x]:
        raise Mismatch(f"with x = {x} got {got}")


def _both(answer, case, cases, fresh=0):
    """(outcome, session, last_probe) batched and one by one, on fresh sessions."""
    out = []
    for runner in (run_cases, one_by_one):
        session = FakeSession(answer)
        ctx = Context(week=3, seed=1, session=session)
        found = runner(ctx, case, cases, fresh)
        out.append((found, session, ctx.last_probe))
    return out


CASES = [{"x": float(k)} for k in range(10)]


def test_one_probe_per_case_goes_in_one_request_in_the_loops_order() -> None:
    (found, batched, last), (plain_found, plain, plain_last) = _both(_double, _check_double, CASES)
    assert found is None and plain_found is None
    assert len(batched.requests) == 1 and len(plain.requests) == 10
    assert batched.probes == plain.probes  # the worker runs the same probes in the same order
    assert last == plain_last == ("double", {"week": 3, "x": 9.0})


def test_a_wrong_answer_in_the_middle_is_the_failing_case_as_in_the_loop() -> None:
    def answer(name: str, args: dict) -> Any:
        return [0.0] if args["x"] in (4.0, 7.0) else [2 * args["x"]]

    (found, _, last), (plain_found, _, plain_last) = _both(answer, _check_double, CASES)
    assert found is not None and plain_found is not None
    assert found[0] == plain_found[0] == 4
    assert str(found[1]) == str(plain_found[1]) == "with x = 4.0 got [0.0]"
    assert last == plain_last == ("double", {"week": 3, "x": 4.0})


def test_a_student_error_is_the_answer_of_its_own_case_only() -> None:
    def answer(name: str, args: dict) -> Any:
        if args["x"] == 6.0:
            raise StudentError("boom", "ValueError", "differential_drive.py", 3)
        return [2 * args["x"]]

    (found, batched, _), (plain_found, _, _) = _both(answer, _check_double, CASES)
    assert found[0] == plain_found[0] == 6
    assert isinstance(found[1], StudentError) and found[1].file == "differential_drive.py"
    assert len(batched.requests) == 1  # the cases after it were answered in the same request


def test_a_timeout_is_attributed_to_the_case_that_hung_and_ends_the_batch() -> None:
    def answer(name: str, args: dict) -> Any:
        if args["x"] == 3.0:
            raise StudentTimeout("no answer within 2 s, the time limit per call")
        return [2 * args["x"]]

    (found, batched, last), (plain_found, _, plain_last) = _both(answer, _check_double, CASES)
    assert found[0] == plain_found[0] == 3 and isinstance(found[1], StudentTimeout)
    assert str(found[1]) == str(plain_found[1])
    assert last == plain_last == ("double", {"week": 3, "x": 3.0})
    assert len(batched.requests) == 1  # nothing is sent again after the case that hung


def test_a_dead_worker_before_a_wrong_answer_does_not_hide_the_wrong_answer() -> None:
    """Case 2 is wrong, case 5 kills the worker: the loop never reaches case 5, and neither may the
    batch's outcome."""
    def answer(name: str, args: dict) -> Any:
        if args["x"] == 5.0:
            raise WorkerDied("it was killed (time or memory limit)")
        return [0.0] if args["x"] == 2.0 else [2 * args["x"]]

    (found, _, _), (plain_found, _, _) = _both(answer, _check_double, CASES)
    assert found[0] == plain_found[0] == 2 and isinstance(found[1], Mismatch)


def _linear(ctx: Context, x: float) -> None:
    """Three probes a case, the third depending on the first two answers (like week 2's linearity)."""
    one = ctx.probe("double", x=1.0)[0]
    two = ctx.probe("double", x=2.0)[0]
    got = ctx.probe("double", x=x + one + two)
    if got != [2 * (x + 6.0)]:
        raise Mismatch(f"with x = {x} got {got}")


def test_cases_with_several_probes_send_one_request_per_probe_of_a_case() -> None:
    (found, batched, last), (plain_found, plain, plain_last) = _both(_double, _linear, CASES)
    assert found is None and plain_found is None
    assert len(batched.requests) == 3 and len(plain.requests) == 30
    assert sorted(map(json.dumps, batched.probes)) == sorted(map(json.dumps, plain.probes))
    assert last == plain_last == ("double", {"week": 3, "x": 15.0})


def test_a_case_that_changes_the_answer_it_was_given_gets_it_fresh_when_run_again() -> None:
    def case(ctx: Context, x: float) -> None:
        first = ctx.probe("double", x=1.0)
        first.append("changed")  # the case's own copy
        second = ctx.probe("double", x=x)
        if first != [2.0, "changed"] or second != [2 * x]:
            raise Mismatch(f"served {first} and {second}")

    (found, _, _), (plain_found, _, _) = _both(_double, case, CASES)
    assert found is None and plain_found is None


def test_a_probe_built_from_a_nan_answer_is_the_same_probe_when_the_case_runs_again() -> None:
    """float("nan") != float("nan"): the check that a case asks the same again must not call a NaN
    computed afresh in each run another question."""
    def answer(name: str, args: dict) -> Any:
        return [math.nan] if args["x"] == 1.0 else [2 * args["x"]]

    def case(ctx: Context, x: float) -> None:
        one = ctx.probe("double", x=1.0)[0]
        got = ctx.probe("double", x=x + one * 0.5)  # a new NaN object each run
        if not math.isnan(got[0]):
            raise Mismatch(f"with x = {x} got {got}")

    (found, _, _), (plain_found, _, _) = _both(answer, case, CASES)
    assert found is None and plain_found is None


def test_fixed_examples_start_without_a_last_probe_as_in_the_loop() -> None:
    def case(ctx: Context, x: float) -> None:
        if x >= 0:
            ctx.probe("double", x=x)
        if x == -2.0:
            raise Mismatch("no probe in this case")

    cases = [{"x": 1.0}, {"x": -2.0}]
    (found, _, last), (plain_found, _, plain_last) = _both(_double, case, cases, fresh=2)
    assert found[0] == plain_found[0] == 1
    assert last is None and plain_last is None  # the second example reset it and probed nothing


def test_a_grader_bug_in_a_case_propagates_as_from_the_loop() -> None:
    def case(ctx: Context, x: float) -> None:
        got = ctx.probe("double", x=x)
        if x == 5.0:
            raise KeyError("a bug in the check")
        if x == 8.0 and got:
            raise Mismatch("later")

    for runner in (run_cases, one_by_one):
        with pytest.raises(KeyError):
            runner(Context(week=3, seed=1, session=FakeSession(_double)), case, CASES)


def test_run_property_sends_a_checks_drawn_cases_in_one_request() -> None:
    session = FakeSession(_double)
    outcome = run_property(Context(week=3, seed=1, session=session), "week3.x", {"x": Floats(-1, 1)},
                           _check_double, examples=[{"x": 0.5}], max_examples=25)
    assert outcome.fraction == 1.0 and outcome.details["cases"] == 25
    assert [len(r) for r in session.requests] == [26]


# The kept wrong versions whose mistakes property checks catch (at least one per week, one with three
# probes a case, one with probes built from the simulator's frames), graded with the probes batched and
# one by one: the whole result must be the same.
SAME_RESULT = ["week2_swapped_wheels", "week2_full_L", "week2_odometry_sin_cos", "week3_no_wrap",
               "week3_integral_no_dt", "week4_transposed_rotation", "week4_ao_error_not_wrapped",
               "week5_blend_jumps", "week6_ties_prefer_last", "week7_progress_point_max"]


@pytest.mark.parametrize("name", SAME_RESULT)
def test_a_wrong_version_gets_the_same_result_batched_and_one_by_one(name: str, tmp_path: Path,
                                                                      monkeypatch) -> None:
    folder = build(name, tmp_path)
    batched = grade_submission(week_of(name), folder, seed=2014)
    assert any(c["status"] != "passed" for c in batched["checks"] if c["kind"] == "property")
    monkeypatch.setattr(properties, "run_cases", one_by_one)
    plain = grade_submission(week_of(name), folder, seed=2014)
    for result in (batched, plain):
        assert set(result.pop("timing")) == {"total_seconds", "checks"}  # wall times: the one difference
        result.pop("time_budget")      # and what the worker's clock measured (calls, seconds): how, not what
    assert json.dumps(batched, sort_keys=True) == json.dumps(plain, sort_keys=True)
