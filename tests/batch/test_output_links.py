"""Issue 30 item 5: nothing under the batch output folder is written, moved or deleted through a link, at
any level (grader.batch.store). With ``gradescope/``, one student's ``gradescope/<stem>/`` or
``superseded/`` replaced by links to outside folders, a resumed batch once wrote students' results.json
outside ``--out``, moved an outside folder and deleted an outside temporary file; now it refuses, naming
the link, and nothing outside changes."""

from __future__ import annotations

import hashlib
import os
import shutil
from pathlib import Path

import pytest
from batch_helpers import StopAfterOne, make_class

from grader.batch import runner, store
from grader.batch.exports import write_exports
from grader.batch.runner import BatchOptions, run_batch
from simiam.safe_write import LinkRefused

FAKE = "batch_fake_grader:fake_grade"


@pytest.fixture(autouse=True)
def fixed_grader(monkeypatch) -> None:
    monkeypatch.setattr(runner, "grader_fingerprint", lambda: "fake-grader")


def snapshot(folder: Path) -> dict[str, str]:
    """Every entry below `folder` (links as links) with what it holds: what must not change."""
    seen = {}
    for path in sorted(folder.rglob("*")):
        rel = str(path.relative_to(folder))
        if path.is_symlink():
            seen[rel] = "-> " + os.readlink(path)
        elif path.is_file():
            seen[rel] = hashlib.sha256(path.read_bytes()).hexdigest()
        else:
            seen[rel] = "folder"
    return seen


def outside_folder(tmp_path: Path) -> Path:
    """Someone else's folder: a stale-looking student folder, a temporary-looking file, a results.json."""
    outside = tmp_path / "outside"
    (outside / "mallory").mkdir(parents=True)
    (outside / "mallory" / "results.json").write_text("theirs\n")
    (outside / ".precious.tmp").write_text("not ours to delete\n")
    (outside / "alice").mkdir()
    (outside / "alice" / ".precious.tmp").write_text("not ours to delete\n")
    return outside


def options(tmp_path: Path, seed: int = 5) -> BatchOptions:
    return BatchOptions(week=3, batch_dir=tmp_path / "class", out=tmp_path / "out", seed=seed, jobs=1,
                        quiet=True, budget_s=30.0)


def _graded(tmp_path: Path) -> Path:
    make_class(tmp_path / "class", {"alice": "score 10", "bob": "score 4"})
    run_batch(options(tmp_path), grade_fn=FAKE)
    return tmp_path / "out"


def _swap(link: Path, target: Path) -> None:
    if link.is_dir():
        shutil.rmtree(link)
    link.parent.mkdir(parents=True, exist_ok=True)
    link.symlink_to(target, target_is_directory=True)


@pytest.mark.parametrize("where", ["gradescope", "gradescope/alice", "superseded", "superseded/gradescope"])
def test_a_resumed_batch_follows_no_link_in_its_output_folder(tmp_path: Path, where: str) -> None:
    out = _graded(tmp_path)
    outside = outside_folder(tmp_path)
    if where.startswith("superseded"):
        (out / "superseded").mkdir(exist_ok=True)
    _swap(out / where, outside)
    before = snapshot(outside)
    # a new seed stopped after one student: the others' files are superseded; then the exports are rebuilt
    refused: LinkRefused | None = None
    try:
        run_batch(options(tmp_path, seed=6), executor=StopAfterOne())
    except LinkRefused as exc:
        refused = exc
    after = snapshot(outside)
    assert after == before, f"outside the output folder: {sorted(set(before.items()) ^ set(after.items()))}"
    assert refused is not None and str(out / where) in str(refused), f"no refusal naming the link: {refused}"
    assert not (out / ".batch.lock").exists()


def test_the_refusal_names_the_link_on_the_command_line(tmp_path: Path, capsys, monkeypatch) -> None:
    out = _graded(tmp_path)
    outside = outside_folder(tmp_path)
    _swap(out / "gradescope", outside)
    before = snapshot(outside)
    real = runner.run_batch
    monkeypatch.setattr(runner, "run_batch", lambda o, **kw: real(o, grade_fn=FAKE))
    args = runner.argparse.Namespace(week="3", batch=str(tmp_path / "class"), out=str(out), seed=7, jobs=1,
                                     quiet=True, force=True, executor="local", scheduler=None,
                                     sandbox="auto", hidden=False, budget=30.0)
    assert runner.main(args) == 2
    assert f"{out / 'gradescope'} is a link, and nothing is written through a link" in capsys.readouterr().err
    assert snapshot(outside) == before


def test_exports_on_their_own_follow_no_link_below_the_folder(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    outside = outside_folder(tmp_path)
    _swap(out / "gradescope", outside)
    before = snapshot(outside)
    result = {"week": 3, "score": 1.0, "max_score": 10.0, "status": "graded", "checks": []}
    with pytest.raises(LinkRefused, match="gradescope is a link"):
        write_exports(out, {"mallory": result}, {"mallory": "mallory"})
    assert snapshot(outside) == before


def test_the_store_moves_and_removes_without_following_links(tmp_path: Path) -> None:
    out = tmp_path / "out"
    outside = outside_folder(tmp_path)
    before = snapshot(outside)
    with store.output_folder(out):
        store.make_folder(out / "history" / "1")
        store.write_atomic(out / "history" / "1" / "a.txt", "a")
        assert store.move(out / "history" / "1", out / "superseded" / "history" / "1")
        assert (out / "superseded" / "history" / "1" / "a.txt").read_text() == "a"
        (out / "superseded" / "history" / "1" / "out").symlink_to(outside)   # a link inside a folder
        assert store.remove(out / "superseded")                              # removes the link, not outside
        assert not store.remove(out / "superseded")
        _swap(out / "history", outside)
        for doing in (lambda: store.write_atomic(out / "history" / "x.txt", "x"),
                      lambda: store.make_folder(out / "history" / "new"),
                      lambda: store.move(out / "history" / "mallory", out / "kept"),
                      lambda: store.remove(out / "history" / ".precious.tmp"),
                      lambda: store.entries(out / "history")):
            with pytest.raises(LinkRefused, match="history is a link"):
                doing()
        assert store.entries(out) == [("history", False)]
    assert snapshot(outside) == before
