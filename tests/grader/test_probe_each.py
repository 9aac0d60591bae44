"""Probes outside property checks that go together (week 2's IR tables, week 4's u_ao loops) are sent in
one request by `Context.probe_each`, and what the check sees is what the loop with one `ctx.probe` a step
gives: the same answers in order, the same failing step and exception, timeouts and student errors raised
at their own probe, the same `ctx.last_probe` (what a replay repeats)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from test_probe_batching import FakeSession
from wrong_submissions import build, week_of

from grader.checks import Context, Mismatch, Outcome, week2, week4
from grader.grading import grade_submission
from grader.sandbox.errors import SandboxError, StudentError, StudentTimeout, WorkerDied


def one_by_one(self: Context, name: str, many: list[dict[str, Any]]):
    """What the checks ran before probe_each: one `probe` (one round trip) a step, sent when reached."""
    for args in many:
        yield self.probe(name, **args)


def _loop(ctx: Context, steps: int) -> list[Any]:
    """A check's loop: every answer must be [2x]; the first wrong one is a Mismatch."""
    seen = []
    for k, got in enumerate(ctx.probe_each("double", [{"x": float(x)} for x in range(steps)])):
        if got != [2.0 * k]:
            raise Mismatch(f"step {k}: {got}")
        seen.append(got)
    return seen


def _both(answer, run, monkeypatch) -> list[tuple[Any, FakeSession, Any]]:
    """(what run(ctx) returned or raised, the session, ctx.last_probe) with probe_each, then one by one."""
    out = []
    for batched in (True, False):
        with monkeypatch.context() as m:
            if not batched:
                m.setattr(Context, "probe_each", one_by_one)
            session = FakeSession(answer)
            ctx = Context(week=2, seed=2014, session=session)
            try:
                found: Any = run(ctx)
            except (Mismatch, SandboxError) as exc:
                found = exc
            out.append((found, session, ctx.last_probe))
    return out


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, BaseException):
        return type(a) is type(b) and str(a) == str(b)
    if isinstance(a, Outcome):
        return (a.fraction, a.message, json.dumps(a.details, sort_keys=True, default=repr)) == (
            b.fraction, b.message, json.dumps(b.details, sort_keys=True, default=repr))
    return a == b


def _double(name: str, args: dict) -> Any:
    return [2 * args["x"]]


def _wrong_at(k: int, error: SandboxError | None = None):
    def answer(name: str, args: dict) -> Any:
        if args["x"] == k:
            if error is not None:
                raise error
            return ["wrong"]
        return [2 * args["x"]]
    return answer


def test_all_steps_go_in_one_request_with_the_loops_answers(monkeypatch) -> None:
    (found, batched, last), (plain_found, plain, plain_last) = _both(_double, lambda c: _loop(c, 6),
                                                                      monkeypatch)
    assert found == plain_found == [[2.0 * k] for k in range(6)]
    assert [len(r) for r in batched.requests] == [6] and [len(r) for r in plain.requests] == [1] * 6
    assert batched.probes == plain.probes
    assert last == plain_last == ("double", {"week": 2, "x": 5.0})


@pytest.mark.parametrize("error", [None, StudentError("ValueError: no", "trace"), StudentTimeout("hung"),
                                   WorkerDied("killed")], ids=["wrong", "student_error", "timeout", "dead"])
def test_a_failure_in_the_middle_is_raised_at_its_own_step(error, monkeypatch) -> None:
    (found, batched, last), (plain_found, _, plain_last) = _both(_wrong_at(3, error), lambda c: _loop(c, 8),
                                                                  monkeypatch)
    assert isinstance(found, Mismatch if error is None else type(error)) and _same(found, plain_found)
    assert last == plain_last == ("double", {"week": 2, "x": 3.0})  # the replay repeats step 3
    assert len(batched.requests) == 1


def test_a_single_probe_is_a_plain_call(monkeypatch) -> None:
    (found, batched, _), _ = _both(_double, lambda c: _loop(c, 1), monkeypatch)
    assert found == [[0.0]] and batched.requests == [[("double", {"week": 2, "x": 0.0})]]


# The checks themselves, on a fake worker: how many requests, and the same outcome, exception and
# last probe as the loop with one probe a step, for right answers and for wrong ones at some step.
def _ir_true(raw: int) -> float:
    """A right get_ir_distances for week 2: the manual's table for its own raw values, else the distance
    (to 0.1 mm) the simulator reads as `raw`."""
    from grader import reference as ref
    from simiam.course.weeks import get_week

    spec = get_week(2).spec
    table = {ref.table_raw(spec, v): d for d, v in ref.IR_TABLE}
    if raw in table:
        return table[raw]
    return min((abs(ref.ir_raw(spec, d / 10000) - raw), d / 10000) for d in range(200, 4000, 2))[1]


@pytest.mark.parametrize("check, probes", [(week2.ir_table, 3), (week2.ir_simulator, 12)])
@pytest.mark.parametrize("case", ["right", "wrong_all", "timeout_third"])
def test_week2_ir_checks_probe_in_one_request_as_the_loop_would(check, probes, case, monkeypatch) -> None:
    calls: list[int] = []

    def answer(name: str, args: dict) -> Any:
        calls.append(1)
        if case == "timeout_third" and len(calls) in (3, 6):  # the third probe, batched then one by one
            raise StudentTimeout("get_ir_distances hung")
        return [_ir_true(r) * (2.0 if case == "wrong_all" else 1.0) for r in args["raw"]]

    (found, batched, last), (plain_found, plain, plain_last) = _both(answer, check, monkeypatch)
    assert _same(found, plain_found) and last == plain_last
    assert [len(r) for r in batched.requests] == [probes]  # sent one by one again, this fails
    # one by one, a wrong table is still read to its end: the hint depends on how many rows are off
    assert len(plain.requests) == {"right": probes, "wrong_all": 1 if check is week2.ir_simulator else probes,
                                   "timeout_third": 3}[case]
    expected = {"right": Outcome, "wrong_all": Mismatch, "timeout_third": StudentTimeout}[case]
    assert isinstance(found, expected), found


def _avoid_answer(gains: list[float], wrong_third: bool = False):
    """AvoidObstacles on a fake worker: u_ao = sum of gain_i times the vector to IR point i (points spread
    out from the robot's position for simplicity); with `wrong_third`, u_ao points the other way when
    sensor 3 reads close (both checks' third probe)."""
    def answer(name: str, args: dict) -> Any:
        assert name == "avoid_obstacles"
        x, y, _ = args["pose"]
        ds = args["distances"]
        points = [[x + d * (i + 1) for i, d in enumerate(ds)], [y + d * (i - 2) for i, d in enumerate(ds)],
                  [1.0] * 5]
        u = [sum(g * (points[0][i] - x) for i, g in enumerate(gains)),
             sum(g * (points[1][i] - y) for i, g in enumerate(gains))]
        if wrong_third and ds[2] < 0.3:
            u = [-u[0] * 3, -u[1] * 3]
        return {"u_ao": u, "ir_distances_wf": points}
    return answer


@pytest.mark.parametrize("check", [week4.symmetric_gains, week4.points_away])
@pytest.mark.parametrize("answer", [_avoid_answer([1, 0.5, 1, 0.5, 1]), _avoid_answer([1, 0.5, 1, 0.4, 1]),
                                    _avoid_answer([-1, -0.5, -1, -0.5, -1]),
                                    _avoid_answer([1, 0.5, 1, 0.5, 1], wrong_third=True)],
                         ids=["symmetric", "asymmetric", "towards", "wrong_third"])
def test_week4_u_ao_checks_probe_in_one_request_as_the_loop_would(check, answer, monkeypatch,
                                                                   request) -> None:
    (found, batched, last), (plain_found, plain, plain_last) = _both(answer, check, monkeypatch)
    assert _same(found, plain_found) and last == plain_last
    assert [len(r) for r in batched.requests] == [6]  # sent one by one again, this fails
    assert batched.probes[: len(plain.probes)] == plain.probes
    fails = {("asymmetric", "symmetric_gains"), ("wrong_third", "symmetric_gains"),
             ("towards", "points_away")}
    which = (request.node.callspec.id.split("-")[0], check.__name__)
    assert found.fraction == (0.0 if which in fails else 1.0)
    if check is week4.points_away and found.fraction == 0.0:  # stopped at sensor 1: the replay repeats that
        assert last[1]["distances"] == [0.06, 0.3, 0.3, 0.3, 0.3] and len(plain.probes) == 2


# The kept wrong versions whose mistakes these checks catch, graded with the probes batched and one by one:
# the whole result must be the same.
SAME_RESULT = ["week2_ir_no_divider", "week2_ir_wrong_divider", "week4_asymmetric_gains",
               "week4_gains_from_readings"]


@pytest.mark.parametrize("name", SAME_RESULT)
def test_a_wrong_version_gets_the_same_result_batched_and_one_by_one(name: str, tmp_path: Path,
                                                                      monkeypatch) -> None:
    folder = build(name, tmp_path)
    aimed = {"week2_ir_no_divider": ("week2.ir.table", "week2.ir.simulator"),
             "week2_ir_wrong_divider": ("week2.ir.table", "week2.ir.simulator"),
             "week4_asymmetric_gains": ("week4.avoid.symmetric_gains",),
             "week4_gains_from_readings": ("week4.avoid.symmetric_gains",)}[name]
    batched = grade_submission(week_of(name), folder, seed=2014)
    failed = {c["id"] for c in batched["checks"] if c["status"] != "passed"}
    assert set(aimed) <= failed, failed
    with monkeypatch.context() as m:
        m.setattr(Context, "probe_each", one_by_one)
        plain = grade_submission(week_of(name), folder, seed=2014)
    for result in (batched, plain):
        assert set(result.pop("timing")) == {"total_seconds", "checks"}  # wall times: the one difference
        result.pop("time_budget")      # and what the worker's clock measured (calls, seconds): how, not what
    assert json.dumps(batched, sort_keys=True) == json.dumps(plain, sort_keys=True)
