"""Fixtures for the report tests: a week-3 result in the contract's shape, its traces, one Chromium per
module."""

from __future__ import annotations

import pytest
from browser import chromium_context, load_synthetic

EVIL = "<script>window.pwned = 1</script><img src=x onerror=\"window.pwned = 2\">"


@pytest.fixture(scope="session")
def synthetic():
    """The synthetic trace generator (tests/data/traces/synthetic.py) as a module."""
    return load_synthetic("simiam_test_synthetic_r")


@pytest.fixture()
def week3_result(synthetic):
    """(result, traces): a failing property, a scenario with two runs (one crashes), an error with output."""
    goal_run = synthetic.load("week3_goal.json")
    crash_run = synthetic.load("week3_crash.json")
    goal_run["meta"]["check_label"] = "goal (1, 1)"
    crash_run["meta"]["check_label"] = "goal (2, -0.3)"
    result = {
        "week": 3, "score": 4.5, "max_score": 10.0, "status": "graded", "seed": 1234,
        "grader_version": "0.1.0+abcdef0123456789", "check_set_hash": "abcdef0123456789",
        "submission": "alice", "isolation": "bwrap", "hidden": False,
        "checks": [
            {"id": "week3.theta_g.quadrants", "name": "θ_g in every quadrant", "kind": "property",
             "visibility": "visible", "points": 1.0, "max_points": 1.0, "status": "passed",
             "message": "", "details": {}},
            {"id": "week3.pid.integral", "name": "integral term uses dt", "kind": "property",
             "visibility": "visible", "points": 0.0, "max_points": 1.5, "status": "failed",
             "message": "with e_k = 0.5, dt = 0.033 your E_k was 0.5, expected 0.0165",
             "details": {"counterexample": {"e_k": 0.5, "dt": 0.033, "E_k": 0.0},
                         "replay": "grade week3 ./alice --check week3.pid.integral "
                                   "--case 'e_k=0.5,dt=0.033'"}},
            {"id": "week3.go_to_goal.reaches_goals", "name": "reaches the goals", "kind": "scenario",
             "visibility": "visible", "points": 3.5, "max_points": 7.0, "status": "failed",
             "message": "goal (1, 1): reached in 11.2 s; goal (2, -0.3): it collided at t = 6.73 s",
             "details": {"runs": [
                 {"goal": [1.0, 1.0], "reached": True, "time_to_goal": 11.2, "final_distance": 0.048,
                  "min_clearance": 0.41, "settle_time": 1.32, "overshoot": 0.04, "collided": False,
                  "problem": ""},
                 {"goal": [2.0, -0.3], "reached": False, "time_to_goal": None, "final_distance": 0.67,
                  "min_clearance": 0.0, "settle_time": 0.45, "overshoot": 0.02, "collided": True,
                  "problem": "it collided at t = 6.73 s"}]}},
            {"id": "week3.ensure_w.keeps_w", "name": "ensure_w keeps ω " + EVIL, "kind": "property",
             "visibility": "visible", "points": 0.0, "max_points": 0.5, "status": "error",
             "message": "ZeroDivisionError in qb_supervisor.py line 42 " + EVIL,
             "details": {"stdout": "debug: " + EVIL + "\n" * 3 + "done"}},
        ],
    }
    traces = {"week3.go_to_goal.reaches_goals": goal_run, "week3.go_to_goal.reaches_goals#2": crash_run}
    return result, traces


@pytest.fixture(scope="module")
def browser_context():
    """A fresh persistent Chromium profile, headless and offline-minded; closed after the module."""
    yield from chromium_context({"width": 1200, "height": 900})
