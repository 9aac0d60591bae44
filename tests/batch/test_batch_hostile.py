"""Issue 10: one student can never stop the class or change another student's result.

Folder- and name-level attacks, each against a batch of honest students (the fake grader, so that only
the batch's own handling is tested): every hostile entry ends as that student's ``invalid`` with a reason,
the honest students are graded, and batch.json is written. Each test also shows the wrong (earlier)
behaviour from tests/data/batch/wrong_batch.py failing the same check.
"""

from __future__ import annotations

import json
import os
import stat
import tempfile
from pathlib import Path

import pytest
from batch_helpers import CASES, HANG_BUDGET_S, StopAfterOne, hostile, make_class, remove_deep_chain

from grader.batch import names, pool, runner, store, submissions, zips
from grader.batch.names import SubmissionRefused, student_stem
from grader.batch.runner import BatchError, BatchOptions, run_batch
from grader.batch.submissions import pack, unpack
from grader.sandbox import leftovers
from grader.sandbox.runner import kill_uid

FAKE = "batch_fake_grader:fake_grade"


@pytest.fixture(autouse=True)
def fixed_grader(monkeypatch) -> None:
    monkeypatch.setattr(runner, "grader_fingerprint", lambda: "fake-grader")


@pytest.fixture(autouse=True)
def flatten_deep_folders(tmp_path: Path):
    """Remove the 1000-deep folder after the test: pytest's own (recursive) clean-up of old temporary
    folders would hit Python's recursion limit on it, in every later pytest run on this machine."""
    yield
    for deep in tmp_path.glob("*/deep"):
        remove_deep_chain(deep)


def options(tmp: Path, **kw) -> BatchOptions:
    base = {"week": 3, "batch_dir": tmp / "class", "out": tmp / "out", "seed": 7, "jobs": 2, "quiet": True,
            "budget_s": 30.0}
    return BatchOptions(**{**base, **kw})


@pytest.mark.parametrize("case", CASES)
def test_a_hostile_entry_is_that_students_invalid(tmp_path: Path, case: str) -> None:
    klass = make_class(tmp_path / "class", {"honest": "score 7", "zz-honest": "score 8"})
    sid = hostile(klass, case)
    report = run_batch(options(tmp_path), grade_fn=FAKE)
    batch = json.loads((tmp_path / "out" / "batch.json").read_text())
    assert batch["counts"] == {"graded": 2, "invalid": 1, "timeout": 0, "crashed": 0}
    assert report["per_student"][sid]["status"] == "invalid"
    stored = json.loads((tmp_path / "out" / f"{student_stem(sid)}.json").read_text())
    assert stored["status"] == "invalid" and len(stored["message"]) > 20     # a reason, not a bare status
    assert (tmp_path / "out" / f"{student_stem(sid)}.html").is_file()
    assert [batch["per_student"][s]["score"] for s in ("honest", "zz-honest")] == [7.0, 8.0]


@pytest.mark.parametrize("case", ["zip_file_and_folder", "zip_long_name", "zip_deep"])
def test_zip_entries_that_cannot_exist_on_disk_really_cannot(tmp_path: Path, case: str, wrong,
                                                             monkeypatch) -> None:
    """Without the name checks these zips reach the grading process, whose unpack fails: the student
    would be ``crashed`` (and a Dask worker would retry them), never ``invalid`` with a reason."""
    (tmp_path / "class").mkdir()
    hostile(tmp_path / "class", case)
    student = submissions.discover(tmp_path / "class")[0]
    assert submissions.read_submission(student).refused
    monkeypatch.setattr(submissions, "check_paths", wrong.accept_every_name)
    monkeypatch.setattr(zips, "check_path", wrong.accept_every_name)
    naive = submissions.read_submission(student)
    assert naive.refused is None
    with pytest.raises((OSError, RecursionError)):
        unpack(pack(naive.files), Path(tempfile.mkdtemp(dir=tmp_path)))


def test_an_unexpected_error_reading_one_submission_is_that_submissions_problem(tmp_path: Path,
                                                                                monkeypatch) -> None:
    make_class(tmp_path / "class", {"a": "score 1", "b": "score 2"})
    real = submissions.read_folder

    def explode(folder: Path, limits: object = None, skipped: list[str] | None = None) -> dict:
        if folder.name == "a":
            raise KeyError("something nobody foresaw")
        return real(folder, limits, skipped)

    monkeypatch.setattr(submissions, "read_folder", explode)
    report = run_batch(options(tmp_path), grade_fn=FAKE)
    assert report["per_student"]["a"]["status"] == "invalid" and report["per_student"]["b"]["score"] == 2.0
    assert "KeyError" in json.loads((tmp_path / "out" / "a.json").read_text())["message"]


IDS = ["alice", "Alice", "ALICE", "batch", "batch.student", "summary", "gradebook", "gradescope", "con",
       "a" * 128, "a" * 127 + "b", "é" * 60, "<img src=x onerror=alert(1)>", "../x", "x.", ".hidden",
       "x" * 64, "x" * 65, "alice~0000", os.fsdecode(b"caf\xe9"), os.fsdecode(b"caf\xe8"), "\ud800", "a b"]


def test_output_names_are_unique_and_short_by_construction(wrong) -> None:
    stems = [student_stem(i) for i in IDS]
    assert len({s.casefold() for s in stems}) == len(IDS)          # unique, also on a case-insensitive disk
    for stem in stems:
        assert len(stem.encode()) <= 80 and not stem.startswith(".") and "/" not in stem
        assert stem.isprintable() and stem.split(".")[0].lower() not in names.RESERVED
    old = [wrong.student_stem_as_id(i) for i in IDS]
    assert len({s.casefold() for s in old}) < len(IDS)               # the old names collide


def test_the_batch_refuses_to_map_two_students_to_one_file(tmp_path: Path, wrong, monkeypatch) -> None:
    make_class(tmp_path / "class", {"batch": "score 1", "batch.student": "score 9"})
    report = run_batch(options(tmp_path), grade_fn=FAKE)             # distinct files today
    assert sorted(r["score"] for r in report["per_student"].values()) == [1.0, 9.0]
    monkeypatch.setattr(runner, "student_stem", wrong.student_stem_as_id)
    with pytest.raises(BatchError, match="would share the output file"):
        run_batch(options(tmp_path, out=tmp_path / "out2"), grade_fn=FAKE)


def test_names_a_student_cannot_use() -> None:
    for bad in (("a",) * 17, ("n" * 129,), ("x\x1bq.py",), ("go_to_goal\u202eyp.py",)):
        with pytest.raises(SubmissionRefused):
            names.check_path(bad)
    for bad_id in ("alice\u200b", "a\u202eb", "evil\x1b[2J", "x" * 129, "caf\udce9"):
        with pytest.raises(SubmissionRefused):
            names.check_student_id(bad_id)
    for good_id in ("alice", "Café Ωmega", "o'brien-2"):
        names.check_student_id(good_id)
    with pytest.raises(SubmissionRefused, match="cannot both exist"):
        names.check_paths(["A.py", "a.py"])
    names.check_paths(["week3/go_to_goal.py", "week3/quickbot.py", "README.md"])   # an honest layout


# ---- item 4: a result stays under a fixed size whatever the worker sends ------------------------------

def test_one_students_files_stay_under_2_mb(tmp_path: Path, monkeypatch, wrong) -> None:
    make_class(tmp_path / "class", {"flood": "flood 6000000", "honest": "score 7"})
    # the flood's result is some 50 MB of JSON through the pipe: up to 7 s with eight busy loops on two
    # cores, and nothing here hangs, so a budget far above that costs nothing
    budget = 120.0
    run_batch(options(tmp_path, budget_s=budget), grade_fn=FAKE)
    out = tmp_path / "out"
    for path in (out / "flood.json", out / "flood.html", out / "gradescope" / "flood" / "results.json"):
        assert path.stat().st_size <= 2_000_000, path
    result = json.loads((out / "flood.json").read_text())
    assert result["score"] == 5.0 and "truncated" in result
    row = next(line for line in (out / "gradebook.csv").read_text().splitlines() if line.startswith("flood"))
    assert len(row) <= 2000
    monkeypatch.setattr(runner, "bound_result", wrong.no_bound)
    run_batch(options(tmp_path, out=tmp_path / "unbounded", budget_s=budget), grade_fn=FAKE)
    assert (tmp_path / "unbounded" / "flood.json").stat().st_size > 2_000_000


# ---- item 9: a killed grading process leaves no student code behind -----------------------------------

@pytest.mark.parametrize("keep", [False, True])
def test_a_killed_grading_process_leaves_no_temp_folder(tmp_path: Path, monkeypatch, wrong, keep) -> None:
    where = tmp_path / "where.txt"
    make_class(tmp_path / "class", {"leaky": f"leak {where}", "honest": "score 3"})
    if keep:
        monkeypatch.setattr(pool, "sweep_scratch", wrong.keep_scratch)
    report = run_batch(options(tmp_path, budget_s=HANG_BUDGET_S), grade_fn=FAKE)
    assert report["per_student"]["leaky"]["status"] == "timeout"
    folder = Path(where.read_text())
    assert folder.is_relative_to(tempfile.gettempdir())
    assert folder.exists() == keep                 # the wrong pool leaves the student's code on disk
    if keep:       # the real sweep, for every slot of this run (pool's is the wrong one here)
        for scratch in Path(tempfile.gettempdir()).glob(f"{pool.SCRATCH_PREFIX}{os.getpid()}-*"):
            leftovers.sweep_scratch(scratch, kill_uid)
        assert not folder.parent.exists()


def test_folders_of_a_dead_runner_are_swept(tmp_path: Path) -> None:
    dead = tmp_path / f"{pool.SCRATCH_PREFIX}999999999-abc"       # no such pid
    alive = tmp_path / f"{pool.SCRATCH_PREFIX}{os.getpid()}-abc"
    for folder in (dead, alive):
        (folder / "simiam-batch-x").mkdir(parents=True)
        (folder / "simiam-batch-x" / "go_to_goal.py").write_text("# student code\n")
    assert pool.sweep_orphans(tmp_path) == [dead]
    assert not dead.exists() and alive.exists()


# ---- item 10: a secret seed per output folder ----------------------------------------------------------

def test_batch_grading_uses_a_secret_seed_kept_with_the_output(tmp_path: Path, monkeypatch, wrong) -> None:
    make_class(tmp_path / "class", {"a": "score 1"})
    first = run_batch(options(tmp_path, seed=None), grade_fn=FAKE)
    other = run_batch(options(tmp_path, seed=None, out=tmp_path / "other"), grade_fn=FAKE)
    seed_file = tmp_path / "out" / store.SEED
    assert stat.S_IMODE(seed_file.stat().st_mode) == 0o600
    assert first["seed"] == json.loads(seed_file.read_text())["seed"] != 2014
    assert first["seed"] != other["seed"]            # not predictable from one folder to the next
    again = run_batch(options(tmp_path, seed=None), grade_fn=FAKE)  # a resume or regrade reuses it
    assert again["seed"] == first["seed"] and again["this_run"]["skipped"] == 1
    fixed = run_batch(options(tmp_path, seed=12), grade_fn=FAKE)     # --seed N fixes one, and it is kept
    assert fixed["seed"] == 12 == run_batch(options(tmp_path, seed=None), grade_fn=FAKE)["seed"]
    monkeypatch.setattr(runner, "folder_seed", wrong.public_seed)
    assert run_batch(options(tmp_path, seed=None, out=tmp_path / "old"), grade_fn=FAKE)["seed"] == 2014


def test_the_grade_command_leaves_the_batch_seed_unset() -> None:
    from grader.cli import _parser

    args = _parser().parse_args(["week3", "--batch", "x"])
    assert BatchOptions.from_args(args).seed is None
    assert BatchOptions.from_args(_parser().parse_args(["week3", "--batch", "x", "--seed", "5"])).seed == 5


# ---- issue 13 item 12: an interrupted regrade never mixes two gradings ---------------------------------

def test_an_interrupted_regrade_never_mixes_two_gradings(tmp_path: Path) -> None:
    make_class(tmp_path / "class", {"a": "score 1", "b": "score 2", "c": "score 3"})
    run_batch(options(tmp_path, seed=5), grade_fn=FAKE)
    out = tmp_path / "out"
    report = run_batch(options(tmp_path, seed=6), executor=StopAfterOne())
    assert report["interrupted"] and report["not_graded"] == ["b", "c"]
    for path in [*out.glob("*.json"), *out.glob("gradescope/*/results.json")]:
        if path.name != "batch.json":
            assert json.loads(path.read_text()).get("seed", 6) == 6, path      # only the current grading
    assert sorted(p.name for p in out.glob("gradescope/*")) == ["a"]
    assert sorted(p.name for p in out.glob("*.html")) == ["a.html", "summary.html"]
    assert json.loads((out / "superseded" / "b.json").read_text())["seed"] == 5   # kept, out of the way
    assert "Not graded yet: b, c" in (out / "summary.html").read_text()
    assert not (out / store.LOCK).exists()                                       # no stale lock
    again = run_batch(options(tmp_path, seed=6), grade_fn=FAKE)
    assert again["incomplete"] == 0 and sorted(p.name for p in out.glob("gradescope/*")) == ["a", "b", "c"]
    assert not (out / store.LOCK).exists()


def test_the_lock_file_goes_with_the_run(tmp_path: Path) -> None:
    out = tmp_path / "out"
    with store.exclusive(out):
        assert (out / store.LOCK).exists()
        with pytest.raises(store.OutputBusy), store.exclusive(out):
            pass
        assert (out / store.LOCK).exists()         # the refused second batch leaves the holder's lock alone
    assert not (out / store.LOCK).exists()
    with store.exclusive(out):                      # and the folder can be locked again
        pass


# ---- issue 21 item 7: a file the grader does not use never costs the grade -------------------------------

def test_a_latin1_name_on_a_file_the_grader_does_not_use_is_skipped_and_said(tmp_path: Path) -> None:
    """``unzip`` of a zip made on Windows writes ``notes_café.txt`` in Latin-1: the student is graded, and
    told the file was skipped. The same bytes on a course file (a folder holding it) still refuse."""
    klass = make_class(tmp_path / "class", {"alice": "score 7", "bob": "score 6"})
    with open(os.path.join(os.fsencode(klass / "alice"), b"notes_caf\xe9.txt"), "wb") as stream:
        stream.write(b"my notes\n")
    bad_folder = os.path.join(os.fsencode(klass / "bob"), b"\xc9tape")
    os.mkdir(bad_folder)
    with open(os.path.join(bad_folder, b"go_to_goal.py"), "wb") as stream:
        stream.write(b"K = 1\n")
    report = run_batch(options(tmp_path), grade_fn=FAKE)
    alice_row = report["per_student"]["alice"]
    assert (alice_row["status"], alice_row["score"]) == ("graded", 7.0)
    alice = json.loads((tmp_path / "out" / "alice.json").read_text())
    assert len(alice["notices"]) == 1 and alice["notices"][0].startswith("notes_caf\ufffd.txt: its name is "
                                                                         "not valid UTF-8")
    assert "skipped" in alice["notices"][0]
    assert report["per_student"]["bob"]["status"] == "invalid"
    bob = json.loads((tmp_path / "out" / "bob.json").read_text())
    assert "not valid UTF-8; rename it" in bob["message"]
    read = submissions.read_submission(submissions.Student("alice", klass / "alice", "folder"))
    assert sorted(read.files) == ["answer.txt"]
    renamed = submissions.content_hash(read.files)              # a rename of the skipped file regrades
    assert read.sha256 != renamed


def test_the_runners_notices_reach_the_students_result(monkeypatch) -> None:
    """What the runner skipped travels in the task and comes first among the result's notices (and so in
    the report, which renders them)."""
    from grader.batch import task as task_module

    monkeypatch.setattr(task_module, "grade_submission", lambda **kw: {"status": "graded",
                                                                         "notices": ["from the grading"]})
    second = task_module.grade_first({"student": "alice", "week": 3, "seed": 1, "hidden": False,
                                      "files": pack({"go_to_goal.py": b"x"}), "notices": ["skipped one"]})
    assert second.args[0]["notices"] == ["skipped one", "from the grading"]
