"""The worker's library with bytecode (grader.sandbox.library): built once per content and shared by the
bubblewrap workers, never served stale, rebuilt when damaged, and out of reach of student code."""

from __future__ import annotations

import errno
import importlib.util
import marshal
import os
import shutil
from pathlib import Path

import pytest
from sandbox_helpers import attack

from grader.sandbox import exposed, isolation, library
from grader.sandbox.isolation import BWRAP

REPO = Path(__file__).resolve().parents[2]
# Only bubblewrap workers share the library and see it through a bind (a subprocess gets a copy of its own).
needs_bwrap = pytest.mark.skipif(not isolation.bwrap_works()[0],
                                 reason="only bubblewrap workers share the library")
NORM = "simiam/control/norm.py"


@pytest.fixture
def cache(tmp_path, monkeypatch) -> Path:
    """A private cache folder, and no library this process already checked."""
    monkeypatch.setenv("SIMIAM_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setattr(library, "_checked", {})
    return tmp_path / "cache" / "worker-library"


@pytest.fixture
def own_norm(tmp_path, monkeypatch) -> Path:
    """simiam/control/norm.py read from a copy the test can change."""
    copy = tmp_path / "norm.py"
    shutil.copy(exposed.source_of(NORM), copy)
    real = exposed.source_of
    monkeypatch.setattr(exposed, "source_of", lambda relative: copy if relative == NORM else real(relative))
    return copy


def _files(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file()}


def test_the_library_holds_every_exposed_file_and_its_bytecode(cache):
    folder = library.shared_library()
    assert folder.parent == cache
    sources = set(exposed.EXPOSED)
    bytecode = {os.path.relpath(importlib.util.cache_from_source(str(folder / r)), folder) for r in sources}
    assert _files(folder) == sources | bytecode
    for relative in exposed.EXPOSED:
        assert (folder / relative).read_bytes() == exposed.source_of(relative).read_bytes()
        pyc = Path(importlib.util.cache_from_source(str(folder / relative))).read_bytes()
        assert pyc[:4] == importlib.util.MAGIC_NUMBER
        assert int.from_bytes(pyc[4:8], "little") == 0b11  # hash-based and checked against the source
        assert pyc[8:16] == importlib.util.source_hash((folder / relative).read_bytes())
    assert all(oct(p.stat().st_mode)[-3:] in ("755", "644") for p in folder.rglob("*"))
    assert library.shared_library() == folder  # reused, not rebuilt


def test_a_changed_source_gets_a_new_library_not_a_stale_one(cache, own_norm):
    first = library.shared_library()
    own_norm.write_text(own_norm.read_text() + "\nCHANGED = 1\n")
    second = library.shared_library()
    assert second != first
    assert (second / NORM).read_text().endswith("CHANGED = 1\n")
    pyc = Path(importlib.util.cache_from_source(str(second / NORM))).read_bytes()
    assert "CHANGED" in marshal.loads(pyc[16:]).co_names
    assert (first / NORM).read_bytes() != (second / NORM).read_bytes()  # the old one is left as it was


def test_an_edit_that_keeps_size_and_mtime_is_not_served_stale(cache, own_norm):
    first = library.shared_library()
    before = os.stat(own_norm)
    text = own_norm.read_text()
    own_norm.write_text(text.replace("import math", "import cmath", 1)[:len(text)].ljust(len(text)))
    os.utime(own_norm, ns=(before.st_atime_ns, before.st_mtime_ns))
    assert os.stat(own_norm).st_size == before.st_size and os.stat(own_norm).st_mtime_ns == before.st_mtime_ns
    second = library.shared_library()
    assert second != first and "import cmath" in (second / NORM).read_text()


def test_a_damaged_library_is_rebuilt(cache):
    folder = library.shared_library()
    (folder / "simiam/robot/dynamics.py").write_text("print('not exposed')\n")
    (folder / NORM).write_text("def norm(v):\n    return 0.0\n")
    library._checked.clear()  # the next grading process
    again = library.shared_library()
    assert again == folder
    assert _files(again) == _files(folder) and not (again / "simiam/robot/dynamics.py").exists()
    assert (again / NORM).read_bytes() == exposed.source_of(NORM).read_bytes()


def test_a_library_another_process_finished_first_is_used(cache, monkeypatch):
    """Two grading processes build the same library at once: the one that renames second keeps the first's."""
    real_write = exposed.write_library

    def racing(into: Path, sources: dict, *, bytecode: bool = False) -> None:
        real_write(into, sources, bytecode=bytecode)
        shutil.copytree(into, os.path.join(os.path.dirname(into), library.library_key(sources)))

    monkeypatch.setattr(exposed, "write_library", racing)
    folder = library.shared_library()
    assert [p.name for p in cache.iterdir()] == [folder.name]  # nothing half-built left behind
    assert library._intact(str(folder), _sources())


def test_without_a_writable_cache_the_library_lives_in_a_private_folder(tmp_path, monkeypatch):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("SIMIAM_CACHE_DIR", str(blocker))
    monkeypatch.setattr(library, "_checked", {})
    folder = library.shared_library()
    assert not str(folder).startswith(str(blocker))
    assert (folder / NORM).read_bytes() == exposed.source_of(NORM).read_bytes()


def test_old_versions_are_pruned_after_a_week(cache, own_norm):
    first = library.shared_library()
    week_ago = os.stat(first).st_mtime - library.STALE_SECONDS - 60
    os.utime(first, (week_ago, week_ago))
    own_norm.write_text(own_norm.read_text() + "\n# another version\n")
    second = library.shared_library()
    assert not first.exists() and second.exists()


@pytest.mark.sandbox
@needs_bwrap
def test_the_worker_imports_the_librarys_bytecode(open_one, cache):
    """The point of the library: the worker's imports read its .pyc (here one whose code differs from its
    source while its header still matches the source; only the cache's owner could write one)."""
    folder = library.shared_library()
    relative = "grader/inside/probes_week6.py"
    pyc = Path(importlib.util.cache_from_source(str(folder / relative)))
    source = (folder / relative).read_text() + "\nFROM_BYTECODE = True\n"
    pyc.write_bytes(pyc.read_bytes()[:16] + marshal.dumps(compile(source, relative, "exec")))
    session = open_one("poison_library")
    assert session.isolation == BWRAP
    assert attack(session, fn="marker", module="grader.inside.probes_week6", name="FROM_BYTECODE") is True


def test_student_code_cannot_change_the_library(open_session, mode, cache):
    first = open_session("poison_library")
    seen = attack(first)
    results = seen["results"]
    assert len(results) == 9
    if mode == BWRAP:
        assert seen["library"] == isolation.LIBRARY
        assert _refused_by_the_mount(results), results
    elif os.geteuid() == 0:
        assert "done" not in results.values(), results  # its own uid; root owns the files
    second = open_session("_honest")
    second.load()
    if mode == BWRAP:
        assert second._library == first._library
        assert library._intact(str(second._library), _sources())
    else:  # a copy per session: what the first student changed is not the second's
        assert second._library != first._library
        assert all((second._library / r).read_bytes() == data for r, data in _sources().items())


def _sources() -> dict[str, bytes]:
    return {r: exposed.source_of(r).read_bytes() for r in exposed.EXPOSED}


@pytest.mark.parametrize("mode", [pytest.param(BWRAP, marks=[pytest.mark.sandbox, needs_bwrap])])
def test_the_test_sees_a_writable_library(open_session, monkeypatch, cache):
    """The wrong version: the library bound read-write. The same attempts then fail for another reason
    (file permissions: the worker's own uid) or succeed, and the test above sees it."""
    real = isolation.plan_worker

    def writable(*args, **kwargs):
        plan = real(*args, **kwargs)
        at = plan.argv.index(isolation.LIBRARY)
        assert plan.argv[at - 2] == "--ro-bind"
        plan.argv[at - 2] = "--bind"
        return plan

    monkeypatch.setattr(isolation, "plan_worker", writable)
    session = open_session("poison_library")
    results = attack(session)["results"]
    assert not _refused_by_the_mount(results), results


def _refused_by_the_mount(results: dict[str, str]) -> bool:
    """Nothing was done, and everything but opening a file (which checks its mode first) met a read-only
    file system, whatever the worker's uid."""
    blocked = {k: v for k, v in results.items() if not k.startswith("append")}
    return "done" not in results.values() and set(blocked.values()) == {os.strerror(errno.EROFS)}
