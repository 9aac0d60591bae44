"""Official grading by default, ``--seed`` from a batch folder, the hidden set's identity, ``--only`` and
``history/`` (issue 29 items 1 and 5), with the fake grader of batch_fake_grader.py."""

from __future__ import annotations

import importlib.util
import json
import shutil
from pathlib import Path

import pytest
from batch_helpers import make_class

from grader.batch import history, runner
from grader.batch.runner import BatchError, BatchOptions, run_batch
from grader.batch.seed import parse_seed
from grader.cli import _parser
from grader.hidden import hidden_dir
from grader.hidden.identity import hidden_set_identity

CALLS = "batch_fake_grader:count_calls"
WRONG = Path(__file__).resolve().parents[1] / "data" / "batch" / "wrong_regrade.py"


def wrong_regrade():
    spec = importlib.util.spec_from_file_location("wrong_regrade", WRONG)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def options(tmp: Path, **kw) -> BatchOptions:
    base = {"week": 3, "batch_dir": tmp / "class", "out": tmp / "out", "seed": 5, "jobs": 1, "quiet": True,
            "budget_s": 30.0}
    return BatchOptions(**{**base, **kw})


def graded(tmp: Path, monkeypatch, **kw) -> tuple[dict, list[str]]:
    """Run the batch with the counting fake grader: (batch.json record, the students it graded)."""
    calls = tmp / "calls.txt"
    calls.write_text("")
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    report = run_batch(options(tmp, **kw), grade_fn=CALLS)
    return report, sorted(calls.read_text().split())


def from_command(*words: str) -> BatchOptions:
    return BatchOptions.from_args(_parser().parse_args(["week3", "--batch", "x", *words]))


def test_a_batch_is_official_unless_visible_only() -> None:
    assert from_command().hidden is True
    assert from_command("--hidden").hidden is True          # accepted for old scripts
    assert from_command("--visible-only").hidden is False
    assert from_command("--only", "b, a,b").only == ("b", "a")


def test_seed_from_a_number_a_batch_folder_its_seed_file_or_what_cat_prints(tmp_path: Path) -> None:
    folder = tmp_path / "graded"
    folder.mkdir()
    (folder / ".seed").write_text(json.dumps({"seed": 918273, "set_by": "random (secret)"}))
    printed = (folder / ".seed").read_text()               # what `cat graded/.seed` prints
    for given in ("918273", str(folder), str(folder) + "/", str(folder / ".seed"), printed):
        assert parse_seed(given) == 918273, given
    assert parse_seed("-3") == -3                         # `grade week3 --seed -3` always worked
    assert from_command("--seed", str(folder)).seed == 918273
    for bad, words in (("7x", "whole number"), (str(tmp_path), "not the output of a batch"),
                       ("1" * 40, "whole number")):
        with pytest.raises(ValueError, match=words):
            parse_seed(bad)
    (folder / ".seed").write_text("[1, 2]")
    with pytest.raises(ValueError, match="holds no seed"):
        parse_seed(str(folder))


def test_every_result_and_batch_json_record_the_seed_and_hidden_set(tmp_path: Path, monkeypatch) -> None:
    make_class(tmp_path / "class", {"a": "score 4", "b": "score 9"})
    report, _ = graded(tmp_path, monkeypatch, week=4, seed=11)
    expected = hidden_set_identity(4, 11)
    assert report["hidden"] is True and report["seed"] == 11 and report["hidden_set"] == expected
    assert len(expected["variants"]) == 3 and expected["file"] == "week4.json"
    for sid in ("a", "b"):
        stored = json.loads((tmp_path / "out" / f"{sid}.json").read_text())
        kept = stored["batch"]["hidden_set"]
        assert kept == {k: v for k, v in expected.items() if k != "variants"}    # no hidden goal in it
        assert stored["seed"] == 11
    visible, _ = graded(tmp_path, monkeypatch, week=4, seed=11, hidden=False, out=tmp_path / "vis")
    assert visible["hidden"] is False and visible["hidden_set"] is None


def test_the_hidden_set_identity_follows_the_data_and_the_draws(tmp_path: Path, monkeypatch) -> None:
    """The variants are those the week's check draws; an edited hidden set changes the digest (and
    regrades the class with "new hidden set"); the same draws under another seed keep it."""
    from grader.checks import week7

    data = json.loads((hidden_dir() / "week7.json").read_text())
    assert hidden_set_identity(7, 3)["variants"] == week7.hidden_picks(data, 3)
    edited = tmp_path / "hidden"
    shutil.copytree(hidden_dir(), edited)
    monkeypatch.setenv("SIMIAM_HIDDEN", str(edited))
    make_class(tmp_path / "class", {"a": "score 4"})
    _, first = graded(tmp_path, monkeypatch, week=4)
    before = hidden_set_identity(4, 5)["digest"]
    week4 = json.loads((edited / "week4.json").read_text())
    week4["variants"] = [dict(v, mirror=not v["mirror"]) for v in week4["variants"]]
    (edited / "week4.json").write_text(json.dumps(week4))
    after = hidden_set_identity(4, 5)["digest"]
    report, second = graded(tmp_path, monkeypatch, week=4)
    assert before != after and first == second == ["a"]
    assert json.loads((tmp_path / "out" / "a.json").read_text())["batch"]["change"]["reasons"] == [
        "new hidden set"]
    monkeypatch.setattr(runner, "hidden_set_identity", wrong_regrade().digest_of_seed_only)
    graded(tmp_path, monkeypatch, week=4, out=tmp_path / "w")
    week4["variants"] = week4["variants"][::-1]
    (edited / "week4.json").write_text(json.dumps(week4))
    assert graded(tmp_path, monkeypatch, week=4, out=tmp_path / "w")[1] == []    # the wrong one: no regrade


def test_only_regrades_the_named_students_even_unchanged(tmp_path: Path, monkeypatch) -> None:
    make_class(tmp_path / "class", {"alice": "score 3", "bob": "score 6", "carol": "score 9"})
    _, first = graded(tmp_path, monkeypatch)
    report, second = graded(tmp_path, monkeypatch, only=("bob",))
    assert first == ["alice", "bob", "carol"] and second == ["bob"]
    assert report["only"] == ["bob"] and report["counts"]["graded"] == 3     # the others' results stay
    bob = json.loads((tmp_path / "out" / "bob.json").read_text())
    assert bob["batch"]["change"]["reasons"] == ["regrade asked with --only"]
    kept = sorted((tmp_path / "out" / "history" / "bob").iterdir())
    assert len(kept) == 1 and json.loads(kept[0].read_text())["score"] == 6.0
    assert not (tmp_path / "out" / "history" / "alice").exists()
    assert report["changed"] == []          # same score: nobody's changed


def test_only_with_an_unknown_id_names_the_near_ones_and_grades_nobody(tmp_path: Path, monkeypatch) -> None:
    make_class(tmp_path / "class", {"alice": "score 3", "bob": "score 6"})
    with pytest.raises(BatchError) as caught:
        graded(tmp_path, monkeypatch, only=("bob", "alcie", "zed"))
    text = str(caught.value)
    assert "'alcie' (did you mean 'alice'?)" in text and "'zed'" in text and "nothing was graded" in text
    assert (tmp_path / "calls.txt").read_text() == "" and not (tmp_path / "out").exists()


def test_history_keeps_every_earlier_result_and_says_whose_score_changed_and_why(tmp_path: Path,
                                                                                monkeypatch) -> None:
    klass = make_class(tmp_path / "class", {"alice": "score 3", "bob": "score 6"})
    graded(tmp_path, monkeypatch)
    (klass / "alice" / "answer.txt").write_text("score 7\n")
    report, again = graded(tmp_path, monkeypatch)
    assert again == ["alice"]
    row = report["changed"][0]
    assert report["changed"] == [{"student": "alice", "before": 3.0, "after": 7.0, "status_before": "graded",
                                  "status_after": "graded", "reasons": ["new submission"],
                                  "at": row["at"], "this_run": True}]
    assert row["at"][:2] == "20", row                        # when alice was graded again
    summary = (tmp_path / "out" / "summary.html").read_text()
    assert "Scores changed by a regrade" in summary and "new submission" in summary and "this run" in summary
    # a run that reuses alice's result still lists her change, but as an earlier regrade's, not this run's
    report, none = graded(tmp_path, monkeypatch)
    assert none == [] and [(r["student"], r["this_run"]) for r in report["changed"]] == [("alice", False)]
    summary = (tmp_path / "out" / "summary.html").read_text()
    assert "this run" not in summary and row["at"][:16].replace("T", " ") in summary
    report, third = graded(tmp_path, monkeypatch, seed=6)
    assert third == ["alice", "bob"] and report["changed"] == []
    out = tmp_path / "out"
    scores = sorted(json.loads(p.read_text())["score"] for p in (out / "history" / "alice").glob("*.json"))
    assert scores == [3.0, 7.0]                   # both earlier gradings of alice, none overwritten
    assert json.loads((out / "bob.json").read_text())["batch"]["change"]["reasons"] == ["new seed"]


@pytest.mark.parametrize("wrong, target", [("archive_nothing", "archive"), ("no_reasons", "reasons")])
def test_the_wrong_bookkeeping_is_caught(wrong: str, target: str, tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setattr(history, target, getattr(wrong_regrade(), wrong))
    with pytest.raises(AssertionError):
        test_history_keeps_every_earlier_result_and_says_whose_score_changed_and_why(tmp_path, monkeypatch)


def test_a_stored_result_with_a_score_that_is_no_number_is_shown_without_one(tmp_path: Path,
                                                                            monkeypatch) -> None:
    """A stored result is data: `NaN` (which Python's JSON reader accepts) must not stop batch.json."""
    klass = make_class(tmp_path / "class", {"alice": "score 3"})
    graded(tmp_path, monkeypatch)
    stored = tmp_path / "out" / "alice.json"
    stored.write_text(stored.read_text().replace('"score": 3.0', '"score": NaN'))
    (klass / "alice" / "answer.txt").write_text("score 4\n")
    report, again = graded(tmp_path, monkeypatch)
    assert again == ["alice"]
    assert (report["changed"][0]["before"], report["changed"][0]["after"]) == (None, 4.0)


def test_a_hidden_set_that_does_not_parse_stops_the_batch_with_its_name(tmp_path: Path, monkeypatch) -> None:
    edited = tmp_path / "hidden"
    shutil.copytree(hidden_dir(), edited)
    (edited / "week4.json").write_text('{"variants": [')
    monkeypatch.setenv("SIMIAM_HIDDEN", str(edited))
    make_class(tmp_path / "class", {"a": "score 4"})
    with pytest.raises(BatchError, match=r"hidden set of week 4 cannot be read .*week4\.json"):
        graded(tmp_path, monkeypatch, week=4)
