"""A whole batch with a fake grader: every student ends with a status and files, reruns resume from the
cache key, --force and a new seed regrade, results do not depend on --jobs, and a batch killed mid-run
loses nothing already graded."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest
from batch_helpers import HANG_BUDGET_S, HERE, StopAfterOne, make_class, make_zip

from grader.batch import cache, pool, runner
from grader.batch.runner import BatchError, BatchOptions, run_batch

FAKE = "batch_fake_grader:fake_grade"
COUNT = "batch_fake_grader:count_calls"
ANSWERS = {"alice": "score 10", "bob": "score 4", "carol": "crash", "dave": "invalid", "erin": "score 7",
           "frank": "raise", "gus": "garbage"}


def options(tmp: Path, **kw) -> BatchOptions:
    base = {"week": 3, "batch_dir": tmp / "class", "out": tmp / "out", "seed": 1234, "jobs": 2, "quiet": True,
            "budget_s": 30.0}
    return BatchOptions(**{**base, **kw})


def without_timing(out: Path) -> dict[str, dict]:
    found = {}
    for path in sorted(out.glob("*.json")):
        if path.name != "batch.json":
            result = json.loads(path.read_text())
            result.pop("timing", None)
            found[path.stem] = result
    return found


@pytest.fixture(autouse=True)
def fixed_grader(monkeypatch) -> None:
    """The fake grader's identity, so that colleagues editing the real grader meanwhile change nothing."""
    monkeypatch.setattr(runner, "grader_fingerprint", lambda: "fake-grader")


@pytest.fixture
def klass(tmp_path: Path) -> Path:
    make_class(tmp_path / "class", ANSWERS, zipped=("erin",))
    (tmp_path / "class" / "gina.zip").write_bytes(b"this is not a zip")
    make_zip(tmp_path / "class" / "hal.zip", {"../../etc/cron.d/x": "evil"})
    return tmp_path


def test_every_student_gets_a_status_and_all_files(klass: Path) -> None:
    report = run_batch(options(klass), grade_fn=FAKE)
    out = klass / "out"
    statuses = {sid: json.loads((out / f"{sid}.json").read_text())["status"]
                for sid in [*ANSWERS, "gina", "hal"]}
    assert statuses == {"alice": "graded", "bob": "graded", "carol": "crashed", "dave": "invalid",
                        "erin": "graded", "frank": "crashed", "gus": "crashed", "gina": "invalid",
                        "hal": "invalid"}
    assert report["counts"] == {"graded": 3, "invalid": 3, "timeout": 0, "crashed": 3}
    assert "no usable result" in json.loads((out / "gus.json").read_text())["message"]
    for sid in statuses:
        assert (out / f"{sid}.html").read_text().strip()
        assert json.loads((out / "gradescope" / sid / "results.json").read_text())["score"] >= 0
    hal = json.loads((out / "hal.json").read_text())
    assert "outside" in hal["message"] and hal["submission"] == "hal.zip"
    assert "status 3" in json.loads((out / "carol.json").read_text())["message"]
    rows = {row["student"]: row for row in csv.DictReader((out / "gradebook.csv").open())}
    assert rows["alice"]["total"] == "10.0" and rows["bob"]["week3.fake.a"] == "4.0"
    assert rows["carol"]["status"] == "crashed" and rows["carol"]["max"] == "10.0"
    summary = (out / "summary.html").read_text()
    assert 'href="alice.html"' in summary and "<svg" in summary
    batch = json.loads((out / "batch.json").read_text())
    assert batch["seed"] == 1234 and batch["students"] == 9 and not batch["interrupted"]


def test_rerun_skips_unchanged_and_regrades_what_changed(klass: Path, tmp_path: Path, monkeypatch) -> None:
    calls = tmp_path / "calls.txt"
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    run_batch(options(klass), grade_fn=COUNT)
    first = set(calls.read_text().split())
    assert first == {"alice", "bob", "carol", "dave", "erin", "frank", "gus"}
    calls.write_text("")
    report = run_batch(options(klass), grade_fn=COUNT)
    # graded and invalid results are reused; crashes are retried (they may be the machine's fault)
    assert set(calls.read_text().split()) == {"carol", "frank", "gus"}
    assert report["this_run"]["skipped"] == 6
    (klass / "class" / "bob" / "answer.txt").write_text("score 5\n")
    calls.write_text("")
    run_batch(options(klass), grade_fn=COUNT)
    assert set(calls.read_text().split()) == {"bob", "carol", "frank", "gus"}
    assert json.loads((klass / "out" / "bob.json").read_text())["score"] == 5.0
    calls.write_text("")
    run_batch(options(klass, force=True), grade_fn=COUNT)
    assert set(calls.read_text().split()) == first
    calls.write_text("")
    run_batch(options(klass, seed=99), grade_fn=COUNT)
    assert set(calls.read_text().split()) == first
    assert json.loads((klass / "out" / "alice.json").read_text())["seed"] == 99


def test_cache_key_covers_every_input(wrong) -> None:
    base = dict(week=3, seed=1, hidden=False, submission_sha256="ab", grader="g")
    for change in ({"week": 4}, {"seed": 2}, {"hidden": True}, {"submission_sha256": "cd"}, {"grader": "h"}):
        assert cache.cache_key(**{**base, **change}) != cache.cache_key(**base), change
    # the same check catches a key that forgets the seed
    assert wrong.cache_key_ignoring_seed(**{**base, "seed": 2}) == wrong.cache_key_ignoring_seed(**base)
    assert not cache.is_fresh({"status": "timeout", "batch": {"cache_key": "k"}}, "k")
    assert cache.is_fresh({"status": "graded", "batch": {"cache_key": "k"}}, "k")


def test_fingerprint_is_recomputed_each_time(monkeypatch) -> None:
    before = cache.grader_fingerprint()
    monkeypatch.setattr(cache, "_package_version", lambda: "9.9.9")
    assert cache.grader_fingerprint().startswith("9.9.9+") and before != cache.grader_fingerprint()


def test_results_do_not_depend_on_jobs(klass: Path) -> None:
    run_batch(options(klass, jobs=1, out=klass / "one"), grade_fn=FAKE)
    run_batch(options(klass, jobs=3, out=klass / "three"), grade_fn=FAKE)
    one, three = without_timing(klass / "one"), without_timing(klass / "three")
    assert one == three and len(one) == 9
    assert (klass / "one" / "gradebook.csv").read_text() == (klass / "three" / "gradebook.csv").read_text()


def test_hung_grading_is_a_timeout(tmp_path: Path) -> None:
    make_class(tmp_path / "class", {"slow": "hang", "quick": "score 2"})
    run_batch(options(tmp_path, budget_s=HANG_BUDGET_S), grade_fn=FAKE)
    slow = json.loads((tmp_path / "out" / "slow.json").read_text())
    assert slow["status"] == "timeout" and slow["score"] == 0.0 and f"{HANG_BUDGET_S:g} s" in slow["message"]
    assert json.loads((tmp_path / "out" / "quick.json").read_text())["status"] == "graded"


def test_bad_batch_folder_and_busy_output(tmp_path: Path) -> None:
    with pytest.raises(BatchError, match="not a folder"):
        run_batch(options(tmp_path), grade_fn=FAKE)
    (tmp_path / "class").mkdir()
    with pytest.raises(BatchError, match="no student"):
        run_batch(options(tmp_path), grade_fn=FAKE)
    with pytest.raises(BatchError, match="not be the class folder"):
        run_batch(options(tmp_path, out=tmp_path / "class"), grade_fn=FAKE)


def test_reserved_ids_and_output_inside_the_class_folder(tmp_path: Path) -> None:
    make_class(tmp_path / "class", {"batch": "score 3", "summary": "score 4"})
    report = run_batch(options(tmp_path, out=tmp_path / "class" / "reports"), grade_fn=FAKE)
    out = tmp_path / "class" / "reports"
    assert report["students"] == 2            # the output folder is not taken for a student
    stems = {json.loads(p.read_text()).get("batch", {}).get("student"): p.stem for p in out.glob("*.json")}
    assert stems["batch"].startswith("batch~") and stems["summary"].startswith("summary~")
    assert json.loads((out / f"{stems['batch']}.json").read_text())["score"] == 3.0
    assert json.loads((out / "batch.json").read_text())["format"] == "simiam-batch/1"
    assert f"{stems['summary']}.html" in (out / "summary.html").read_text()


RUNNER = """
import sys, argparse
sys.path.insert(0, {here!r})
from grader.batch import runner
runner.grader_fingerprint = lambda: "fake-grader"
args = argparse.Namespace(week=3, batch={klass!r}, out={out!r}, jobs=1, force=False, quiet=True, seed=5,
                          hidden=False, executor="local", scheduler=None)
runner.DEFAULT_BUDGET_S = 60
import grader.batch.runner as r
orig = r.run_batch
r.run_batch = lambda o, **kw: orig(o, grade_fn="batch_fake_grader:fake_grade")
sys.exit(runner.main(args))
"""


def start_runner(tmp_path: Path) -> subprocess.Popen:
    # d writes where it copied its files as it starts, then hangs: the sign that d is being graded
    answers = {"a": "score 1", "b": "score 2", "c": "score 3", "d": f"leak {tmp_path / 'd-began'}",
               "e": "sleep 60"}
    make_class(tmp_path / "class", answers)
    code = RUNNER.format(here=str(HERE), klass=str(tmp_path / "class"), out=str(tmp_path / "out"))
    return subprocess.Popen([sys.executable, "-c", code], start_new_session=True)


def wait_for(path: Path) -> None:
    for _ in range(600):
        if path.exists():
            return
        time.sleep(0.05)
    raise AssertionError(f"{path} never appeared")


@pytest.mark.parametrize("how", [signal.SIGKILL, signal.SIGTERM])
def test_killed_batch_keeps_what_was_graded_and_resumes(tmp_path: Path, how: int, monkeypatch) -> None:
    proc = start_runner(tmp_path)
    wait_for(tmp_path / "out" / "c.json")
    wait_for(tmp_path / "d-began")            # d is being graded now
    os.kill(proc.pid, how)
    code = proc.wait(timeout=30)
    assert code == (130 if how == signal.SIGTERM else -signal.SIGKILL)
    scratch = list(Path(tempfile.gettempdir()).glob(f"{pool.SCRATCH_PREFIX}{proc.pid}-*"))
    # a clean stop deletes its grading processes' temporary folders; a SIGKILL leaves them to the next run
    assert scratch == [] if how == signal.SIGTERM else len(scratch) >= 1
    out = tmp_path / "out"
    assert {p.stem for p in out.glob("*.json")} - {"batch"} == {"a", "b", "c"}
    assert [json.loads((out / f"{s}.json").read_text())["score"] for s in "abc"] == [1.0, 2.0, 3.0]
    if how == signal.SIGTERM:                 # a clean stop also rebuilds the class files
        batch = json.loads((out / "batch.json").read_text())
        assert batch["interrupted"] and batch["incomplete"] == 2
        assert len((out / "gradebook.csv").read_text().splitlines()) == 4
    for sid in "de":
        (tmp_path / "class" / sid / "answer.txt").write_text("score 4\n")
    calls = tmp_path / "calls.txt"
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    report = run_batch(options(tmp_path, seed=5), grade_fn=COUNT)
    assert not any(path.exists() for path in scratch)           # swept by the next run
    assert sorted(calls.read_text().split()) == ["d", "e"]
    assert report["counts"]["graded"] == 5 and not report["interrupted"]


def test_a_zip_of_every_week_is_graded_from_the_batch_weeks_folder(tmp_path: Path) -> None:
    (tmp_path / "class").mkdir()
    make_zip(tmp_path / "class" / "ann.zip", {"assignments/week3/go_to_goal.py": "3", "assignments/week3/"
                                              "answer.txt": "score 7", "assignments/week4/go_to_goal.py": "4",
                                              "assignments/week4/avoid_obstacles.py": "4",
                                              "assignments/week4/answer.txt": "score 1"})
    run_batch(options(tmp_path), grade_fn=FAKE)
    result = json.loads((tmp_path / "out" / "ann.json").read_text())
    assert result["batch"]["root"] == "assignments/week3" and result["score"] == 7.0


def test_results_of_an_older_grading_stay_out_of_the_class_files(tmp_path: Path) -> None:
    make_class(tmp_path / "class", {"a": "score 1", "b": "score 2", "c": "score 3"})
    run_batch(options(tmp_path, seed=5), grade_fn=FAKE)
    report = run_batch(options(tmp_path, seed=6), executor=StopAfterOne())   # a new seed, stopped at once
    assert report["interrupted"] and report["incomplete"] == 2 and sum(report["counts"].values()) == 1
    rows = list(csv.DictReader((tmp_path / "out" / "gradebook.csv").open()))
    assert [r["student"] for r in rows] == ["a"]
    assert "2 submissions not graded yet" in (tmp_path / "out" / "summary.html").read_text()
    again = run_batch(options(tmp_path, seed=6), grade_fn=FAKE)                # the rerun finishes the job
    assert again["incomplete"] == 0 and again["this_run"] == {"graded_now": 2, "skipped": 1}


def test_a_second_batch_on_the_same_output_is_refused(tmp_path: Path) -> None:
    from grader.batch.store import exclusive

    make_class(tmp_path / "class", {"a": "score 1"})
    with exclusive(tmp_path / "out"), pytest.raises(BatchError, match="another batch"):
        run_batch(options(tmp_path), grade_fn=FAKE)
    assert run_batch(options(tmp_path), grade_fn=FAKE)["counts"]["graded"] == 1


def test_exit_status_of_main(tmp_path: Path, monkeypatch) -> None:
    import argparse

    real = runner.run_batch
    monkeypatch.setattr(runner, "run_batch", lambda o, **kw: real(o, grade_fn=FAKE))
    make_class(tmp_path / "class", {"a": "score 1", "b": "score 2"})
    args = argparse.Namespace(week="week3", batch=str(tmp_path / "class"), out=str(tmp_path / "out"), jobs=1,
                              force=False, quiet=True, seed=3, hidden=False, executor="local", scheduler=None)
    assert runner.main(args) == 0
    (tmp_path / "class" / "c").mkdir()
    (tmp_path / "class" / "c" / "answer.txt").write_text("invalid")
    assert runner.main(args) == 1
    assert runner.main(argparse.Namespace(**{**vars(args), "week": "week9"})) == 2


def test_a_regrade_starts_with_the_students_who_took_far_longest(tmp_path: Path, monkeypatch) -> None:
    """So a hung or very slow submission does not run alone at the end while the other processes idle.
    Over twice the median plus 5 s counts (b, d); the others, and f never graded here, keep their order."""
    make_class(tmp_path / "class", {sid: "score 1" for sid in "abcdef"})
    run_batch(options(tmp_path, jobs=1), grade_fn=FAKE)
    out = tmp_path / "out"
    for sid, seconds in {"a": 1.0, "b": 60.0, "c": 1.0, "d": 30.0, "e": 1.0}.items():
        stored = json.loads((out / f"{sid}.json").read_text())
        stored["timing"]["batch_seconds"] = seconds
        (out / f"{sid}.json").write_text(json.dumps(stored))
    (out / "f.json").unlink()
    calls = tmp_path / "calls"
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    run_batch(options(tmp_path, jobs=1, force=True), grade_fn="batch_fake_grader:count_calls")
    assert calls.read_text().split() == ["b", "d", "a", "c", "e", "f"]
