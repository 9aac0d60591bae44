"""Issue 30 item 6: a stored result is checked before it is reused (grader.batch.stored). A result with a
valid cache key but a wrong type (``"points": "abc"``) once stopped a resumed batch in summary.py with
"could not convert string to float", and the class files were not rebuilt; now it is regraded, never
trusted, and the class files are built from the regraded result."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from batch_helpers import make_class

from grader.batch import runner
from grader.batch.runner import BatchOptions, run_batch
from grader.batch.stored import problem
from grader.batch.summary import summary_html

COUNT = "batch_fake_grader:count_calls"


def _points(result: dict) -> None:
    result["checks"][0]["points"] = "abc"


def _max_points(result: dict) -> None:
    result["checks"][1]["max_points"] = [1]


def _score(result: dict) -> None:
    result["score"] = "ten"


def _checks(result: dict) -> None:
    result["checks"] = {"id": "x"}


def _check(result: dict) -> None:
    result["checks"].append("passed")


def _infinite(result: dict) -> None:
    result["score"] = float("inf")  # written by json.dumps as Infinity, which json.loads reads back


def _late(result: dict) -> None:
    result["late"] = {"penalty_points": "all"}


SPOILERS = [_points, _max_points, _score, _checks, _check, _infinite, _late]


@pytest.fixture(autouse=True)
def fixed_grader(monkeypatch) -> None:
    monkeypatch.setattr(runner, "grader_fingerprint", lambda: "fake-grader")


@pytest.mark.parametrize("spoil", SPOILERS, ids=lambda f: f.__name__.strip("_"))
def test_a_malformed_stored_result_is_regraded_not_trusted(tmp_path: Path, monkeypatch, spoil) -> None:
    make_class(tmp_path / "class", {"alice": "score 10", "bob": "score 4"})
    calls = tmp_path / "calls.txt"
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    options = BatchOptions(week=3, batch_dir=tmp_path / "class", out=tmp_path / "out", seed=1234, jobs=1,
                           quiet=True, budget_s=30.0)
    run_batch(options, grade_fn=COUNT)
    stored = tmp_path / "out" / "alice.json"
    result = json.loads(stored.read_text())
    spoil(result)                                      # the cache key stays valid
    stored.write_text(json.dumps(result))
    calls.write_text("")
    report = run_batch(options, grade_fn=COUNT)
    assert calls.read_text().split() == ["alice"], "the malformed result was reused, not regraded"
    again = json.loads(stored.read_text())
    assert again["score"] == 10.0 and problem(again) is None
    assert report["counts"]["graded"] == 2 and report["incomplete"] == 0
    assert "alice" in (tmp_path / "out" / "summary.html").read_text()
    gradebook = (tmp_path / "out" / "gradebook.csv").read_text()
    assert "alice,4.0,6.0,0.0,10.0,10.0,graded" in gradebook, gradebook


@pytest.mark.parametrize("spoil", SPOILERS, ids=lambda f: f.__name__.strip("_"))
def test_the_summary_leaves_out_what_it_cannot_read(spoil) -> None:
    good = {"week": 3, "score": 4.0, "max_score": 10.0, "status": "graded",
            "checks": [{"id": "week3.a", "status": "passed", "points": 4.0, "max_points": 4.0},
                       {"id": "week3.b", "status": "failed", "points": 0.0, "max_points": 6.0}]}
    bad = json.loads(json.dumps(good))
    spoil(bad)
    assert problem(good) is None
    assert problem(bad), f"nothing found wrong with {bad}"
    page = summary_html({"bob": good, "mallory": bad}, {"bob": "bob", "mallory": "mallory"}, {"week": 3})
    assert "bob" in page and "mallory" not in page
