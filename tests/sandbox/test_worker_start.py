"""What a worker's start imports (issue 15: its CPU). numpy stays (the course's quickbot.py calls np.polyval
every step); modules that only some error message or a base class needed are kept out of the preloads."""

from __future__ import annotations

from grader.inside import worker
from grader.sandbox import exposed

# module -> who pulled it in before, and what it cost every worker start (CPU, after numpy)
COSTLY = {
    "importlib.abc": "simiam.course.loader's finder base class: importlib.resources, tempfile, shutil, "
                     "bz2, lzma, random; 10-18 ms",
    "importlib.resources": "the same",
    "tempfile": "the same",
    "difflib": "simiam.control.supervisor's 'did you mean': 1.8 ms",
}
WORKER_MODULES = ["grader.inside.probes"]  # what a grading worker preloads besides the test probes


def _loaded(session) -> set[str]:
    assert session.load()["errors"] == []
    return set(session.call("probe", name="modules", args={"extra": WORKER_MODULES}))


def _preloads_stdlib(session) -> bool:
    """True where the worker's uid cannot read the Python environment (root, Python under /root, no
    bubblewrap): it then preloads every standard module a student or an error message may import later."""
    return bool(session._worker.plan.config.get("preload_stdlib"))


def test_a_worker_start_imports_none_of_the_costly_modules(open_session):
    """In each mode this machine has (with bubblewrap and without it); the standard modules the private-
    environment mode preloads on purpose (grader.inside.worker._STDLIB, difflib among them) are its price
    for not being able to import them after the uid drop, not a regression."""
    session = open_session("_honest")
    loaded = _loaded(session)
    assert {"numpy", "simiam.control", "simiam.course.loader", "grader.inside.worker_loop",
            "grader.inside.probes"} <= loaded
    deliberate = set(worker._STDLIB) if _preloads_stdlib(session) else set()
    costly = set(COSTLY) - deliberate
    assert loaded.isdisjoint(costly), sorted(loaded & costly)
    assert {"importlib.abc", "tempfile"} <= costly  # the loader's finder stays out in every mode


def test_the_private_environment_mode_preloads_what_its_messages_import(open_session):
    """Where nothing can be imported after the drop, the "did you mean" of a misspelt setting still needs
    difflib: the preload list keeps it (the first test's exemption is exactly this list)."""
    session = open_session("_honest")
    loaded = _loaded(session)
    if _preloads_stdlib(session):
        assert "difflib" in loaded, "difflib not preloaded: a misspelt setting's hint would fail to import"
    else:
        assert "difflib" not in loaded, "difflib preloaded where it can be imported when needed"


def test_the_test_sees_a_costly_import(open_one, monkeypatch, tmp_path):
    """The wrong version: the loader's finder derived from importlib.abc.MetaPathFinder again."""
    wrong = tmp_path / "loader.py"
    text = exposed.source_of("simiam/course/loader.py").read_text()
    wrong.write_text(text.replace("class _SubmissionFinder:", "import importlib.abc\n\n\n"
                                  "class _SubmissionFinder(importlib.abc.MetaPathFinder):"))
    assert wrong.read_text() != text
    real = exposed.source_of
    monkeypatch.setattr(exposed, "source_of",
                        lambda relative: wrong if relative == "simiam/course/loader.py" else real(relative))
    loaded = _loaded(open_one("_honest"))
    assert {"importlib.abc", "tempfile"} <= loaded
