"""Issue 22, item 6: what student code prints while a hidden check runs goes only where that check's result
goes, with its visibility; never into the result's top-level student_output (Gradescope's "What your code
printed", PrairieLearn's `output`).

The attack (tests/data/attacks/graded/print_hidden_goals.patch) prints every goal its controller is given,
each with the three it saw before (kept in a module global), in lines short enough that the top-level
output as it was (its first and last lines) showed the hidden goals, printed last.
Graded in both isolation modes.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from mistakes import build

from grader.grading import grade_submission
from grader.platforms import gradescope, prairielearn
from grader.sandbox.isolation import BWRAP, SUBPROCESS, bwrap_works

SEED = 918273645
MODES = [pytest.param(BWRAP, marks=[pytest.mark.sandbox,
                                    pytest.mark.skipif(not bwrap_works()[0], reason="no bubblewrap here")]),
         SUBPROCESS]


def hidden_goals(result: dict) -> list[tuple[float, float]]:
    """The goals of the hidden checks' runs, as the checks record them."""
    goals = []
    for check in result["checks"]:
        if check["visibility"] == "visible":
            continue
        details = check["details"]
        runs = details.get("runs") or [details]
        goals += [tuple(run["goal"]) for run in runs if run.get("goal")]
    return goals


def shown(goal: tuple[float, float]) -> list[str]:
    """How the attack prints a goal: first on its own line, then among the goals seen before a later one."""
    x, y = goal
    return [f"GOAL {x} {y}", f"({x}, {y})"]


@pytest.fixture(scope="module", params=MODES)
def graded(request, tmp_path_factory) -> dict:
    folder = build("attacks/graded", "print_hidden_goals", tmp_path_factory.mktemp("attack"))
    return grade_submission(3, folder, seed=SEED, hidden=True, sandbox=request.param)


def test_the_attack_prints_the_hidden_goals_into_the_hidden_checks_only(graded):
    goals = hidden_goals(graded)
    assert len(goals) >= 2 and graded["status"] == "graded"
    printed_hidden = "\n".join(c.get("printed", "") for c in graded["checks"] if c["visibility"] != "visible")
    for goal in goals:
        assert not any(text in graded["student_output"] for text in shown(goal)), goal
        assert any(text in printed_hidden for text in shown(goal)), "the attack did not run in hidden checks"
    assert "GOAL 1 1" in graded["student_output"]   # the visible checks' goals are shown as before
    assert not any(c.get("printed") for c in graded["checks"] if c["visibility"] == "visible")


@pytest.mark.parametrize("choice", ["hidden", "after_published", "visible"])
def test_gradescope_shows_them_only_in_the_hidden_tests_with_their_visibility(graded, choice):
    config = {"week": 3, "hidden_visibility": choice, "hidden_checks": 2}
    out = gradescope.results_json(graded, config, 1.0)
    kinds = [c["visibility"] for c in graded["checks"]]
    pairs = list(zip(out["tests"], kinds, strict=True))
    hidden = [t for t, kind in pairs if kind != "visible"]
    visible_text = out["output"] + json.dumps([t for t, kind in pairs if kind == "visible"])
    for goal in hidden_goals(graded):
        assert not any(text in visible_text for text in shown(goal)), goal
        assert any(text in t["output"] for t in hidden for text in shown(goal))
    assert len(hidden) == 2 and {t["visibility"] for t in hidden} == {choice}
    assert all("What your code printed during this check" in t["output"] for t in hidden)


def test_prairielearn_shows_them_nowhere(graded):
    text = json.dumps(prairielearn.results_json(graded))
    for goal in hidden_goals(graded):
        assert not any(part in text for part in shown(goal)), goal
    assert "GOAL 1 1" in text


def test_an_honest_week_prints_nothing_into_its_hidden_checks(tmp_path: Path):
    root = Path(__file__).resolve().parents[2]
    result = grade_submission(3, root / "solutions" / "week3", seed=SEED, hidden=True)
    assert result["score"] == result["max_score"]
    assert not any("printed" in c for c in result["checks"])
