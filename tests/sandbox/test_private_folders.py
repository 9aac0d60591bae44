"""Issue 20 item 5: grading works, and says truthfully what the worker could read, when the grader's files or
its temporary folder sit inside a folder only its owner can open (0700: a home folder, a CI workspace).

As root, a plain-subprocess worker runs under a dedicated uid that reaches only what every user can reach
(grader.sandbox.reach). Before, its copy of the submission and its library went into TMPDIR whatever that
was: with TMPDIR in a private folder the worker could import neither, and the grading blamed the student
("none of your files could be loaded ... no such week"). Each layout here is made under tmp_path with an
explicit chmod 700 on an ancestor, so the test does not depend on where the checkout happens to live.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
from sandbox_helpers import (
    AS_ROOT,
    HONEST,
    LIMITS,
    PROBES,
    attack,
    honest_probe,
    make_submission,
    open_marker,
    says_it_reads,
)

from grader.batch import pool
from grader.grading import grade_submission
from grader.sandbox import isolation, reach
from grader.sandbox.errors import StudentError
from grader.sandbox.isolation import BWRAP, SUBPROCESS
from grader.sandbox.session import StudentSession

REPO = Path(__file__).resolve().parents[2]


def _private(tmp_path: Path) -> Path:
    """A folder only root (the owner) can open, as a home folder is: a uid without privileges cannot even
    pass through it, whatever the permissions of what is inside."""
    home = tmp_path / "home"
    home.mkdir()
    home.chmod(0o700)
    return home


@pytest.fixture
def private_tmpdir(tmp_path, monkeypatch) -> Path:
    """TMPDIR inside a private folder (tempfile.gettempdir() follows tempfile.tempdir)."""
    folder = _private(tmp_path) / "tmp"
    folder.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(folder))
    return folder


def test_a_worker_starts_when_the_temporary_folder_is_private(private_tmpdir, shared_dir, mode):
    with StudentSession(1, make_submission(shared_dir, "_honest"), LIMITS, sandbox=mode,
                        probes="sandbox_probes", extra_paths=(str(PROBES),)) as session:
        assert session.load()["errors"] == []
        assert honest_probe(session) == pytest.approx(HONEST)
        work = session._work._root
        if mode == SUBPROCESS and AS_ROOT:  # read in place by the worker's uid: somewhere it can enter
            assert reach.enterable(work) and not work.is_relative_to(private_tmpdir.parent)


def test_grading_with_a_private_temporary_folder_gives_full_marks(private_tmpdir, mode):
    result = grade_submission(week=1, submission=REPO / "solutions" / "week1", seed=1, sandbox=mode)
    assert (result["status"], result["score"]) == ("graded", result["max_score"]), result.get("message")
    assert result["isolation"] == mode


def test_without_a_temporary_folder_it_can_enter_the_grader_says_so(private_tmpdir, shared_dir, monkeypatch):
    """Not the student's fault, and not a mystery: the session refuses to start and names the fix."""
    if not AS_ROOT:
        pytest.skip("without root the worker runs as the grader's own user, which enters its own TMPDIR")
    from grader.sandbox import workdir
    from grader.sandbox.errors import SandboxUnavailable

    monkeypatch.setattr(workdir, "SHARED_TEMP", (str(private_tmpdir),))
    session = StudentSession(1, make_submission(shared_dir, "_honest"), LIMITS, sandbox=SUBPROCESS,
                             probes="sandbox_probes", extra_paths=(str(PROBES),))
    with pytest.raises(SandboxUnavailable, match="set TMPDIR to a folder every user may enter"):
        session.load()
    session.close()
    assert list(private_tmpdir.glob("simiam-work-*")) == []  # the refused copy is not left behind


def test_batch_scratch_folders_go_where_the_workers_uid_can_enter(private_tmpdir):
    slot = pool._Slot("grader.batch.task:grade_task")
    try:
        slot.ensure_running()
        assert slot.scratch is not None
        if AS_ROOT:
            assert reach.enterable(slot.scratch)
        assert pool.sweep_orphans() == []   # looked where the pool puts them: this runner is alive
    finally:
        slot.close()


def _layout(base: Path) -> dict[str, Path]:
    """A checkout's grader file and solution, world-readable as git leaves them."""
    files = {"the grader's files": base / "checkout" / "grader" / "reference.py",
             "solutions/": base / "checkout" / "solutions" / "week1" / "differential_drive.py"}
    for path in files.values():
        path.parent.mkdir(parents=True)
        path.write_text("# the answer\n")
        path.chmod(0o644)
    return files


@pytest.mark.parametrize("where", ["private", "open"])
def test_the_note_says_truthfully_what_the_worker_can_read(open_session, mode, tmp_path, shared_dir,
                                                           monkeypatch, where):
    """The attack reads a checkout's files laid out in a private folder or an open one: under bubblewrap
    nothing of it exists; in a plain subprocess the note names exactly what the worker could read, and as
    root (a dedicated uid) nothing inside the private folder."""
    files = _layout(_private(tmp_path) if where == "private" else shared_dir / "open")
    notes = {name: path.parent.parent if name == "solutions/" else path for name, path in files.items()}
    monkeypatch.setattr(isolation, "course_files", lambda: notes)
    session = open_session("read_solutions")
    paths = [str(p) for p in files.values()]
    if mode == BWRAP:
        with pytest.raises(StudentError, match="No such file"):
            attack(session, paths=paths)
        return
    marker = open_marker(shared_dir)
    found = attack(session, paths=[*paths, str(marker)])
    assert str(marker) in found
    for name, path in files.items():
        assert (str(path) in found) == says_it_reads(session.isolation_note, name), session.isolation_note
    if where == "private" and AS_ROOT:
        assert not set(paths) & set(found)
