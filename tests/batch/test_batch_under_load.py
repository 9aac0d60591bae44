"""A student whose grading the machine spoiled (grader.under_load) is reported to the instructor: in
batch.json's `under_load`, in the batch's printed output and per student as they finish; and the next run
of the same command grades them again instead of reusing the spoiled result."""

from __future__ import annotations

import io
import json
from pathlib import Path

import pytest
from batch_helpers import make_class

from grader.batch import runner
from grader.batch.runner import BatchOptions, run_batch

COUNT = "batch_fake_grader:count_calls"


@pytest.fixture(autouse=True)
def fixed_grader(monkeypatch) -> None:
    monkeypatch.setattr(runner, "grader_fingerprint", lambda: "fake-grader")


def test_students_graded_under_load_are_listed_and_regraded(tmp_path: Path, monkeypatch) -> None:
    make_class(tmp_path / "class", {"alice": "score 10", "bob": "under_load", "carol": "score 4"})
    calls = tmp_path / "calls.txt"
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    printed = io.StringIO()
    monkeypatch.setattr("sys.stderr", printed)
    monkeypatch.setattr("sys.stdout", printed)
    options = BatchOptions(week=3, batch_dir=tmp_path / "class", out=tmp_path / "out", seed=1, jobs=1,
                           quiet=False, budget_s=30.0)
    report = run_batch(options, grade_fn=COUNT)
    text = printed.getvalue()
    print(text)
    assert report["under_load"] == ["bob"]
    assert json.loads((tmp_path / "out" / "batch.json").read_text())["under_load"] == ["bob"]
    assert "graded under load, regrade: 1 student(s)" in text and "(bob)" in text
    assert "bob: graded under load: regrade (week3.fake.b" in text
    calls.write_text("")
    run_batch(options, grade_fn=COUNT)  # the same submissions, the same grader: only bob is graded again
    assert calls.read_text().split() == ["bob"]


def test_a_malformed_under_load_record_read_back_counts_as_none() -> None:
    assert runner.under_load({"under_load": {"checks": "x"}}) == []
    assert runner.under_load({"under_load": {"checks": ["a\x1b[2J", 3]}}) == ["a\\x1b[2J", "3"]
    assert runner.under_load({"under_load": {"checks": []}}) == ["?"]
