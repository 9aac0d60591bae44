"""The gradebook and the class summary say, per student, why points were lost when the whole submission
failed (files missing, a syntax error, an unreadable zip): never an empty message."""

from __future__ import annotations

import csv
import shutil
from pathlib import Path

import mistakes

from grader.batch.runner import BatchOptions, run_batch

ROOT = Path(__file__).resolve().parents[2]


def test_every_student_who_lost_points_has_a_reason(tmp_path: Path) -> None:
    klass = tmp_path / "class"
    klass.mkdir()
    shutil.copytree(ROOT / "solutions" / "week3", klass / "full")
    (klass / "nothing").mkdir()
    (klass / "nothing" / "notes.py").write_text("# my notes, no assignment files\n")
    mistakes.build("submissions", "loader_syntax_error", klass, 3, "syntax")
    (klass / "broken.zip").write_bytes(b"PK\x03\x04 this is not a zip")
    run_batch(BatchOptions(week=3, batch_dir=klass, out=tmp_path / "out", seed=1, quiet=True, jobs=1))
    rows = {r["student"]: r for r in csv.DictReader((tmp_path / "out" / "gradebook.csv").open())}
    assert set(rows) == {"full", "nothing", "syntax", "broken"}
    assert rows["full"]["message"] == "" and rows["full"]["total"] == rows["full"]["max"]
    for sid in ("nothing", "syntax", "broken"):
        assert rows[sid]["message"].strip(), sid
    # no course file at all: invalid (issue 29 item 8), not a zero-point grading
    assert rows["nothing"]["status"] == "invalid"
    assert "holds none of week 3's files" in rows["nothing"]["message"]
    assert "notes.py" in rows["nothing"]["message"]
    assert "SyntaxError" in rows["syntax"]["message"] or "syntax" in rows["syntax"]["message"].lower()
    summary = (tmp_path / "out" / "summary.html").read_text()
    assert "holds none of week 3&#39;s files" in summary
