"""Property checks draw their cases without Hypothesis (grader/domains.py) and bring it in only to shrink:
the same seed tries the same cases, the edges are tried, and a failure is still shrunk or at least kept."""

from __future__ import annotations

import math
import subprocess
import sys
import textwrap

import pytest

from grader.checks import Context, Mismatch
from grader.domains import Floats, Integers, Lists, Row, SampledFrom
from grader.properties import run_property
from grader.sandbox.errors import StudentTimeout


def _tried(check_id: str, domains: dict, seed: int = 1, cases: int = 25) -> list[dict]:
    seen: list[dict] = []

    def case(ctx: Context, **inputs) -> None:
        seen.append(inputs)

    outcome = run_property(Context(week=3, seed=seed, session=None), check_id, domains, case,
                           max_examples=cases)
    assert outcome.fraction == 1.0 and outcome.details["cases"] == cases == len(seen)
    return seen


def test_the_same_seed_tries_the_same_cases_and_another_seed_others() -> None:
    domains = {"v": Floats(-0.5, 0.5), "ticks": Lists(Row(Integers(-4, 4), Integers(-4, 4)), 1, 10),
               "dt": SampledFrom([0.01, 0.05])}
    first = _tried("week3.x", domains)
    assert first == _tried("week3.x", domains)
    assert first != _tried("week3.x", domains, seed=2) and first != _tried("week3.y", domains)
    for inputs in first:
        assert -0.5 <= inputs["v"] <= 0.5 and 1 <= len(inputs["ticks"]) <= 10 and inputs["dt"] in (0.01, 0.05)
        assert all(-4 <= t <= 4 for pair in inputs["ticks"] for t in pair)


def test_the_simplest_case_and_both_bounds_come_first_and_edges_recur() -> None:
    domains = {"theta": Floats(-math.pi, math.pi)}
    tried = [c["theta"] for c in _tried("week4.avoid.heading", domains, cases=200)]
    assert tried[:3] == [0.0, -math.pi, math.pi]
    later = tried[3:]
    assert any(abs(t) >= math.nextafter(math.pi, 0) for t in later)  # the bounds again, not only once
    assert any(abs(t) < 1e-4 for t in later if t)  # tiny values, as Hypothesis favours
    assert len(set(later)) > 100  # and mostly uniform draws


@pytest.mark.parametrize("wrong_at", [math.pi, -math.pi, 0.0])
def test_a_mistake_that_shows_only_at_an_edge_is_found(wrong_at: float) -> None:
    def case(ctx: Context, theta: float, x: float) -> None:
        if theta == wrong_at:
            raise Mismatch(f"with theta = {theta} the error was not wrapped")

    outcome = run_property(Context(week=4, seed=2014, session=None), "week4.avoid.heading",
                           {"theta": Floats(-math.pi, math.pi), "x": Floats(0.5, 1.0)}, case, max_examples=15)
    assert outcome.fraction == 0.0
    assert outcome.details["counterexample"]["theta"] == wrong_at
    assert "--check week4.avoid.heading --case 'theta=" in outcome.details["replay"]


def test_a_failure_is_shrunk_by_hypothesis_into_the_smallest_case() -> None:
    def case(ctx: Context, ticks: list) -> None:
        if len(ticks) >= 3:
            raise Mismatch(f"with {len(ticks)} steps your estimate drifted")

    outcome = run_property(Context(week=2, seed=7, session=None), "week2.odometry.drift",
                           {"ticks": Lists(Row(Integers(-4, 4), Integers(-4, 4)), 1, 10)}, case)
    assert outcome.fraction == 0.0
    assert outcome.details["counterexample"] == {"ticks": [[0, 0], [0, 0], [0, 0]]}
    assert outcome.message == "with 3 steps your estimate drifted"


def test_a_failure_hypothesis_cannot_find_again_is_reported_as_drawn() -> None:
    """An answer that is wrong only the first time it is asked: Hypothesis's search sees it pass, but the
    check must not pass on that account."""
    calls = []

    def case(ctx: Context, v: float) -> None:
        calls.append(v)
        if len(calls) == 1:
            raise Mismatch(f"with v = {v} your vel_r was wrong")

    outcome = run_property(Context(week=2, seed=1, session=None), "week2.uni_to_diff.round_trip",
                           {"v": Floats(-0.3, 0.3)}, case)
    assert outcome.fraction == 0.0
    assert outcome.details["counterexample"] == {"v": 0.0}
    assert outcome.message == "with v = 0.0 your vel_r was wrong"
    assert len(calls) > 1  # Hypothesis did search


def test_a_timeout_among_the_drawn_cases_stops_at_once_and_says_so() -> None:
    calls = []

    def case(ctx: Context, x: float) -> None:
        calls.append(x)
        if len(calls) == 2:
            raise StudentTimeout("no answer within 2 s, the time limit per call")

    outcome = run_property(Context(week=3, seed=1, session=None), "week3.pid.integral",
                           {"x": Floats(-1, 1)}, case)
    assert outcome.fraction == 0.0 and outcome.status == "timeout" and len(calls) == 2
    assert outcome.message == ("your code did not answer in time: "
                               "no answer within 2 s, the time limit per call")
    assert outcome.details["counterexample"] == {"x": -1.0}


def test_a_filtered_domain_never_draws_what_it_leaves_out() -> None:
    tried = _tried("week2.uni_to_diff.spin", {"w": Floats(-5.0, 5.0).filter(lambda w: abs(w) > 1e-2)},
                   cases=200)
    assert all(abs(c["w"]) > 1e-2 for c in tried)
    assert tried[1]["w"] == -5.0 and tried[2]["w"] == 5.0


def test_passing_property_checks_never_import_hypothesis() -> None:
    """Hypothesis's import (0.1-0.3 s) is paid only when a case fails."""
    code = textwrap.dedent("""
        import sys
        from grader.checks import Context
        from grader.checks.week3 import CHECKS
        from grader.domains import Floats
        from grader.properties import run_property
        outcome = run_property(Context(week=3, seed=1, session=None), "week3.x", {"x": Floats(0, 1)},
                               lambda ctx, x: None)
        assert outcome.fraction == 1.0, outcome
        print(sorted(m for m in sys.modules if m.split(".")[0] == "hypothesis"))
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
