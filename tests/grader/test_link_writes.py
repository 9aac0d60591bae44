"""Issue 22 items 4 and 5: the grader never writes through a link, and never at a temporary name anyone could
predict or plant first (simiam.safe_write).

The attacks: a student's week folder whose reports/weekN.json and weekN.html are links to files outside it
(`grade` overwrote both targets), and links planted at the temporary names `.weekN.zip.<pid>.tmp` of
`grade handout` and `.<name>.<pid>.tmp` of the batch store (each overwrote the link's target). The writers
as they were are kept in tests/data/wrong_writes.py; each one falls for the same attack here, and the walk
of grader/ and simiam/ below finds every writer that does not go through safe_write.
"""

from __future__ import annotations

import ast
import importlib.util
import json
import os
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest

from grader.batch import store
from grader.grading import write_outputs
from grader.platforms.archive import write_zip
from grader.report.html import write_report
from simiam import safe_write
from simiam.safe_write import LinkRefused
from simiam.trace import Trace
from simiam.viewer.replay import write_replay

REPO = Path(__file__).resolve().parents[2]
DATA = REPO / "tests" / "data"
KEPT = "the instructor's own file"
RESULT = {"week": 2, "score": 0.0, "max_score": 1.0, "status": "graded", "seed": 1, "grader_version": "x",
          "submission": "alice", "message": "", "checks": [
              {"id": "week2.x", "name": "x", "kind": "property", "visibility": "visible", "points": 0.0,
               "max_points": 1.0, "status": "failed", "message": "m", "details": {}}]}
TRACE = json.loads((DATA / "traces" / "week3_goal.json").read_text())


def _wrong():
    spec = importlib.util.spec_from_file_location("wrong_writes", DATA / "wrong_writes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# Every trusted writer of a file at a name in a folder it did not make: (the file's name, write it there).
WRITERS: dict[str, tuple[str, Callable[[Path], object]]] = {
    "safe_write": ("out.txt", lambda d: safe_write.write_text(d / "out.txt", "x")),
    "batch store": ("batch.json", lambda d: store.write_json(d / "batch.json", {"a": 1})),
    "batch secret": (".seed", lambda d: store.folder_seed(d, None)),
    "zip (handout, Gradescope)": ("week1.zip", lambda d: write_zip(d / "week1.zip", {"a": b"x"})),
    "grade's result": ("week2.json", lambda d: write_outputs(RESULT, {}, d)),
    "report": ("week2.html", lambda d: write_report(RESULT, None, d / "week2.html")),
    "replay": ("week3.html", lambda d: write_replay(TRACE, d / "week3.html")),
    "simiam run's trace": ("week3.csv", lambda d: Trace.from_json(TRACE).write(d, stem="week3")),
}


@pytest.fixture
def victim(tmp_path) -> Path:
    """A file outside the folder written into, which a planted link points at."""
    path = tmp_path / "elsewhere" / "precious.txt"
    path.parent.mkdir()
    path.write_text(KEPT)
    return path


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_a_link_at_the_final_name_is_refused(tmp_path, victim, writer):
    name, write = WRITERS[writer]
    folder = tmp_path / "reports"
    folder.mkdir()
    (folder / name).symlink_to(victim)
    with pytest.raises(LinkRefused, match=f"{name} is a link"):
        write(folder)
    assert victim.read_text() == KEPT
    assert not [p.name for p in folder.iterdir() if p.name.endswith(".tmp")]  # nothing left half-done


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_a_link_at_the_folder_is_refused(tmp_path, victim, writer):
    name, write = WRITERS[writer]
    (tmp_path / "reports").symlink_to(victim.parent)
    with pytest.raises(LinkRefused, match="reports is a link"):
        write(tmp_path / "reports")
    assert [p.name for p in victim.parent.iterdir()] == ["precious.txt"]


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_planted_temporary_names_are_never_written_through(tmp_path, victim, writer):
    name, write = WRITERS[writer]
    folder = tmp_path / "out"
    folder.mkdir()
    for pid in {os.getpid(), os.getppid(), 1, 2}:  # the old pattern, for this process and its neighbours
        (folder / f".{name}.{pid}.tmp").symlink_to(victim)
    write(folder)
    assert victim.read_text() == KEPT
    assert (folder / name).is_file() and not (folder / name).is_symlink()


def test_a_temporary_name_already_taken_is_drawn_again(tmp_path, victim, monkeypatch):
    """Even a planted link at the random name itself is never opened: O_CREAT | O_EXCL | O_NOFOLLOW."""
    draws = iter(["planted", "free"])
    monkeypatch.setattr(safe_write.secrets, "token_hex", lambda n: next(draws))
    (tmp_path / ".out.txt.planted.tmp").symlink_to(victim)
    safe_write.write_text(tmp_path / "out.txt", "mine")
    assert victim.read_text() == KEPT and (tmp_path / "out.txt").read_text() == "mine"


def test_without_descriptor_relative_calls_the_same_links_are_refused(tmp_path, victim, monkeypatch):
    """Windows has no O_NOFOLLOW and no dir_fd (only simiam run and migrate may run there): by path."""
    monkeypatch.setattr(safe_write, "_AT_FOLDER", False)
    (tmp_path / "reports").symlink_to(victim.parent)
    (tmp_path / "out.txt").symlink_to(victim)
    (tmp_path / f".new.txt.{os.getpid()}.tmp").symlink_to(victim)
    for path in (tmp_path / "out.txt", tmp_path / "reports" / "out.txt"):
        with pytest.raises(LinkRefused):
            safe_write.write_text(path, "x")
    safe_write.write_text(tmp_path / "new.txt", "mine", mode=0o600)
    assert victim.read_text() == KEPT and (tmp_path / "new.txt").read_text() == "mine"
    assert (tmp_path / "new.txt").stat().st_mode & 0o777 == 0o600


def test_a_secret_is_written_with_its_mode(tmp_path):
    path = safe_write.write_text(tmp_path / "secret.json", "{}", mode=0o600)
    assert path.stat().st_mode & 0o777 == 0o600


@pytest.mark.parametrize("wrong", ["write_atomic", "write_zip", "write_outputs"])
def test_the_old_writers_wrote_through_planted_links(tmp_path, victim, wrong):
    old = getattr(_wrong(), wrong)
    folder = tmp_path / "out"
    folder.mkdir()
    if wrong == "write_outputs":
        (folder / "week2.json").symlink_to(victim)
        old(RESULT, folder)
    else:
        (folder / f".out.{os.getpid()}.tmp").symlink_to(victim)
        old(folder / "out", *(("x",) if wrong == "write_atomic" else ({"a": b"x"},)))
    assert victim.read_bytes() != KEPT.encode()


# ---- the attacks, through the commands -------------------------------------------------------------------
def test_grade_in_a_folder_with_planted_links_writes_through_none(tmp_path, victim, monkeypatch, capsys):
    """Issue 22 item 4: `grade week1` in a student's week1/ whose reports/week1.json and week1.html are
    links to files outside it (the issue's was week 5; the writing is the same for every week)."""
    from grader.cli import main

    other = victim.with_name("other.html")
    other.write_text(KEPT)
    student = tmp_path / "week1"
    shutil.copytree(REPO / "solutions" / "week1", student)
    (student / "reports").mkdir()
    (student / "reports" / "week1.json").symlink_to(victim)
    (student / "reports" / "week1.html").symlink_to(other)
    (student / "graded.json").symlink_to(victim)
    monkeypatch.chdir(student)
    assert main(["week1", ".", "--json", "graded.json"]) == 2
    assert victim.read_text() == KEPT and other.read_text() == KEPT
    err = capsys.readouterr().err
    assert "not written: reports/week1.json is a link" in err and "graded.json is a link" in err
    shutil.rmtree(student / "reports")
    (student / "reports").symlink_to(victim.parent)  # the folder itself a link
    assert main(["week1", "."]) == 2
    assert sorted(p.name for p in victim.parent.iterdir()) == ["other.html", "precious.txt"]
    assert "reports is a link" in capsys.readouterr().err


def test_grade_handout_never_writes_through_a_planted_temporary_name(tmp_path, victim):
    """Issue 22 item 5: `.week1.zip.<pid>.tmp` planted as a link beside the handout's zip."""
    from grader.platforms.cli import main

    out = tmp_path / "release"
    out.mkdir()
    (out / f".week1.zip.{os.getpid()}.tmp").symlink_to(victim)
    assert main(["handout", "week1", "--out", str(out), "--course", str(REPO)]) == 0
    assert victim.read_text() == KEPT
    assert (out / "week1.zip").is_file() and not (out / "week1.zip").is_symlink()


def test_a_link_at_the_batch_lock_is_refused(tmp_path, victim):
    out = tmp_path / "out"
    out.mkdir()
    (out / store.LOCK).symlink_to(victim.with_name("made-by-the-lock"))
    with pytest.raises(LinkRefused), store.exclusive(out):
        pass
    assert not victim.with_name("made-by-the-lock").exists()


# ---- every writer in grader/ and simiam/ ----------------------------------------------------------------
# Writers that need no safe_write, and why. Everything else that writes a file must go through it.
FRESH = "writes into a folder this run made itself (tempfile.mkdtemp / TemporaryDirectory)"
ALLOWED = {
    ("grader/batch/store.py", "move"): "moves the batch's own files within its output folder, descriptor-"
                                       "relative with every level below it opened O_NOFOLLOW (issue 30)",
    ("grader/batch/store.py", "_open_lock"): "os.open with O_NOFOLLOW",
    ("grader/batch/export_files.py", "_read_file"): "os.open read-only with O_NOFOLLOW: reads a platform "
                                                    "download, writes nothing",
    ("grader/batch/submissions.py", "unpack"): FRESH + ": the grading process's copy of a submission",
    ("grader/earlier.py", "reference_folder"): FRESH,
    ("grader/grading.py", "_splice"): FRESH,
    ("grader/platforms/bundle.py", "stage_common"): FRESH + ": the package's staging folder",
    ("grader/platforms/coursera.py", "build"): FRESH + ", moved into an --out that must be empty",
    ("grader/platforms/gradescope.py", "build"): FRESH + " (the zip itself: write_zip)",
    ("grader/platforms/handout.py", "build_handout"): FRESH + ", renamed into place (the zip: write_zip)",
    ("grader/platforms/handout.py", "copy_handout"): FRESH + ": a package's staging folder",
    ("grader/platforms/official.py", "write_secret"): FRESH + ": the package's staging folder",
    ("grader/platforms/official.py", "grade_upload"): FRESH,
    ("grader/platforms/prairielearn.py", "build"): FRESH + ", moved into an --out that must be empty",
    ("grader/platforms/selfcheck.py", "_expectations"): FRESH,
    ("grader/platforms/wheel.py", "build_wheel"): FRESH,
    ("grader/platforms/wrong_versions.py", "apply_mistake"): FRESH + ": selfcheck's copy of a solution",
    ("grader/sandbox/exposed.py", "write_library"): FRESH + ": the worker's library being built",
    ("grader/sandbox/library.py", "_ensure"): FRESH + ", renamed into the private cache (0700)",
    ("grader/sandbox/workdir.py", "__init__"): FRESH + ": the worker's copy of the submission",
    ("simiam/course/migrate.py", "write_atomically"): "tempfile.mkstemp (random, exclusive, no link), then "
                                                      "os.replace in the student's own folder",
    ("simiam/course/skeletons/__init__.py", "write_skeleton"): FRESH + ": the grading's stubs",
    ("simiam/course/splice.py", "splice_folder"): FRESH + ": the grading's spliced files",
    ("simiam/run.py", "fill_missing_files"): FRESH + ": simiam run's copy of the folder",
    ("simiam/safe_write.py", "replacing"): "the one careful writer",
    ("simiam/safe_write.py", "_replacing_by_path"): "the same, where there is no O_NOFOLLOW (Windows)",
    ("simiam/safe_write.py", "_create_temporary"): "os.open with O_EXCL and O_NOFOLLOW",
}
_METHODS = {"write_text", "write_bytes", "rename", "replace", "touch", "symlink_to", "hardlink_to"}
_MODULE_CALLS = {("os", "replace"), ("os", "rename"), ("os", "symlink"), ("os", "link"), ("shutil", "copy"),
                 ("shutil", "copy2"), ("shutil", "copyfile"), ("shutil", "copytree"), ("shutil", "move")}
_WRITE_FLAGS = {"O_WRONLY", "O_RDWR", "O_CREAT", "O_TRUNC", "O_APPEND"}


def _writing_mode(node: ast.Call, position: int) -> bool:
    mode = node.args[position] if len(node.args) > position else \
        next((k.value for k in node.keywords if k.arg == "mode"), None)
    return isinstance(mode, ast.Constant) and isinstance(mode.value, str)\
        and bool(set(mode.value) & set("wax+"))


def _writes(node: ast.Call) -> str | None:
    """What `node` writes with, if it writes a file (not through safe_write)."""
    f = node.func
    if isinstance(f, ast.Name):
        return "open" if f.id == "open" and _writing_mode(node, 1) else None
    if not isinstance(f, ast.Attribute) or (isinstance(f.value, ast.Name) and f.value.id == "safe_write"):
        return None
    module = f.value.id if isinstance(f.value, ast.Name) else None
    if (module, f.attr) in _MODULE_CALLS:
        return f"{module}.{f.attr}"
    if module == "os" and f.attr == "open":  # read-only only when its flags are spelt out in the call
        flags = {n.attr for n in ast.walk(node) if isinstance(n, ast.Attribute) and n.attr.startswith("O_")}
        return "os.open" if not flags or flags & _WRITE_FLAGS else None
    if f.attr == "replace" and (len(node.args) != 1 or node.keywords):
        return None  # str.replace(old, new): two arguments; Path.replace(target) has one
    if f.attr in _METHODS or (f.attr == "open" and _writing_mode(node, 0)):
        return f".{f.attr}"
    return None


def writers(path: Path) -> list[tuple[str, str]]:
    """(function, call) for each call in `path` that writes a file other than through safe_write."""
    found = []
    for function in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
            found += [(function.name, f"{call} (line {node.lineno})") for node in ast.walk(function)
                      if isinstance(node, ast.Call) and (call := _writes(node))]
    return found


def test_every_writer_of_the_grader_and_simiam_writes_safely_or_into_its_own_folder():
    found = []
    for path in sorted(p for package in ("grader", "simiam") for p in (REPO / package).rglob("*.py")):
        relative = path.relative_to(REPO).as_posix()
        if "compiled" not in path.parts:
            found += [f"{relative}:{function}: {call}" for function, call in writers(path)
                      if (relative, function) not in ALLOWED]
    assert found == [], "write these through simiam.safe_write, or say in ALLOWED why they need not"
    stale = [key for key in ALLOWED if key[1] not in {function for function, _ in writers(REPO / key[0])}]
    assert stale == [], "ALLOWED names writers that no longer write"


def test_the_walk_finds_each_old_writer():
    assert {function for function, _ in writers(DATA / "wrong_writes.py")} == \
        {"write_atomic", "write_zip", "write_outputs"}
