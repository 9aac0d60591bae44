"""Issue 10, done means: a class folder holding every hostile submission of the issue plus honest students
grades to completion with ``--jobs 2`` and the real grader: every student has a status, honest students'
results are identical to grading them alone, no file outside the output folder changes, no temporary
folder with student code stays behind, and no page of the class runs script in headless Chromium."""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import sys
import tempfile
import zipfile
from pathlib import Path

import pytest
from batch_helpers import CASES, hostile, remove_deep_chain

from grader.batch import pool
from grader.batch.names import student_stem
from grader.batch.runner import BatchOptions, run_batch

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))
import mistakes  # noqa: E402  (tests/mistakes.py: wrong versions as patches against solutions/)

pytest.importorskip("grader.grading")
SOLUTION = ROOT / "solutions" / "week2"
XSS_ID = "<img src=x onerror=alert('id')>"
XSS_FILE = "<img src=x onerror=alert('file')>.py"
HONEST = ("honest", "honest-zip", XSS_ID, "odd-file")
CODE_ATTACKS = ("fake_output", "hostile_text", "forge_files")
TABS = 10  # pages open at once in the browser check: one wait covers them all


def tree(folder: Path) -> dict[str, str]:
    """Every entry under ``folder`` (links not followed, the 1000-deep chain walked without recursion):
    path -> hash of its bytes, or the link's target, or "dir"."""
    found = {}
    for dirpath, dirnames, filenames in os.walk(folder, followlinks=False):
        if os.path.relpath(dirpath, folder).count(os.sep) > 24:
            dirnames[:] = []                   # os.walk recurses: stop well before Python's limit
        for name in dirnames + filenames:
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, folder)
            if os.path.islink(path):
                found[rel] = "link:" + os.readlink(path)
            elif os.path.isdir(path):
                found[rel] = "dir"
            else:
                found[rel] = hashlib.sha256(Path(path).read_bytes()).hexdigest()
    return found


def honest_entries(klass: Path) -> None:
    shutil.copytree(SOLUTION, klass / "honest")
    with zipfile.ZipFile(klass / "honest-zip.zip", "w") as archive:
        for path in sorted(SOLUTION.glob("*.py")):
            archive.write(path, f"week2/{path.name}")
    shutil.copytree(SOLUTION, klass / XSS_ID)                     # a hostile name, honest code
    shutil.copytree(SOLUTION, klass / "odd-file")                 # an extra file with a hostile name
    (klass / "odd-file" / XSS_FILE).write_text("print('not part of the assignment')\n")


@pytest.fixture(scope="module", params=["auto", "subprocess"])
def graded(tmp_path_factory, request) -> dict:
    """The class graded once per isolation mode ("auto" is bubblewrap where it works)."""
    base = tmp_path_factory.mktemp(f"trust-{request.param}")
    klass = base / "class"
    klass.mkdir()
    honest_entries(klass)
    for name in CODE_ATTACKS:
        folder = mistakes.build("attacks/graded", name, base / "built", 2)
        text = (folder / "differential_drive.py").read_text()
        text = text.replace("__TARGET__", str(base / "outside")).replace("__DELAY__", "0.5")
        (folder / "differential_drive.py").write_text(text)
        shutil.copytree(folder, klass / name)
    (base / "outside").mkdir()
    ids = {case: hostile(klass, case) for case in CASES}
    try:
        yield _grade(base, klass, ids, request.param)
    finally:
        remove_deep_chain(klass / "deep")


def _grade(base: Path, klass: Path, ids: dict, sandbox: str) -> dict:
    before = tree(base)
    mine = set(Path(tempfile.gettempdir()).glob(f"{pool.SCRATCH_PREFIX}{os.getpid()}-*"))
    options = {"week": 2, "seed": 5, "quiet": True, "budget_s": 240.0, "jobs": 2, "sandbox": sandbox}
    report = run_batch(BatchOptions(batch_dir=klass, out=base / "out", **options))
    after = tree(base)
    left = set(Path(tempfile.gettempdir()).glob(f"{pool.SCRATCH_PREFIX}{os.getpid()}-*")) - mine
    alone = base / "alone"
    alone.mkdir()
    for sid in HONEST:
        entry = klass / (sid + ".zip" if sid == "honest-zip" else sid)
        (shutil.copy if entry.is_file() else shutil.copytree)(entry, alone / entry.name)
    alone_report = run_batch(BatchOptions(batch_dir=alone, out=base / "alone-out", **options))
    return {"base": base, "report": report, "alone": alone_report, "ids": ids, "before": before,
            "after": after, "left": left}


def stored(out: Path, sid: str) -> dict:
    result = json.loads((out / f"{student_stem(sid)}.json").read_text())
    result.pop("timing", None)
    result.pop("time_budget", None)   # what the worker's clock measured: how it ran, not what
    return result


def test_every_student_has_a_status(graded) -> None:
    report, ids = graded["report"], graded["ids"]
    statuses = {sid: r["status"] for sid, r in report["per_student"].items()}
    assert report["students"] == len(HONEST) + len(CODE_ATTACKS) + len(CASES) == len(statuses)
    assert {ids[case]: statuses[ids[case]] for case in CASES} == {ids[case]: "invalid" for case in CASES}
    assert all(statuses[sid] == "graded" for sid in HONEST + CODE_ATTACKS), statuses
    full = report["per_student"]["honest"]["score"]
    assert full > 0 and all(report["per_student"][sid]["score"] == full for sid in HONEST)
    assert all(report["per_student"][sid]["score"] < full for sid in CODE_ATTACKS)
    assert (graded["base"] / "out" / "batch.json").is_file()


def test_honest_students_get_what_they_get_alone(graded) -> None:
    out, alone = graded["base"] / "out", graded["base"] / "alone-out"
    for sid in HONEST:
        assert stored(out, sid) == stored(alone, sid), sid


def test_nothing_outside_the_output_folder_changes(graded) -> None:
    changed = {p for p in graded["before"].keys() | graded["after"].keys()
               if graded["before"].get(p) != graded["after"].get(p)
               and not p.startswith(("out", "alone"))}
    assert changed == set()
    assert graded["left"] == set()           # no grading process's temporary folder (student code) is left


def test_no_page_of_the_class_runs_script(graded) -> None:
    """Issue 10 item 2 (escaping: the display branch), checked on the whole hostile class: ids, file
    names, prints and exception text carry <img onerror> and <script> payloads."""
    browser = pytest.importorskip("browser")
    out = graded["base"] / "out"
    pages = sorted(p for p in out.rglob("*.html") if "superseded" not in p.parts)
    assert len(pages) > len(HONEST)
    ran: list[str] = []
    context = browser.chromium_context({"width": 1000, "height": 800})
    ctx = next(context)
    try:
        for first in range(0, len(pages), TABS):
            opened = []
            for page_path in pages[first:first + TABS]:
                page = ctx.new_page()
                page.on("dialog", lambda dialog, p=page_path: (ran.append(f"{p.name}: {dialog.message}"),
                                                               dialog.dismiss()))
                page.goto(page_path.as_uri())
                page.wait_for_load_state("load")
                opened.append(page)
            # an <img onerror> fires once the broken image fails: each page closes 200 ms or more after load
            opened[-1].wait_for_timeout(200)
            for page in opened:
                page.close()
    finally:
        next(context, None)
    assert ran == []
