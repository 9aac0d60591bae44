"""What students upload to a platform, in any layout, becomes one folder of their week files; hostile
layouts are refused with a reason (the batch runner's checks, reused)."""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

import pytest
from mistakes import ROOT

from grader.platforms.intake import SubmissionRefused, collect

WEEK3 = ROOT / "solutions" / "week3"
NAMES = sorted(p.name for p in WEEK3.glob("*.py"))


def _copy(into: Path) -> None:
    into.mkdir(parents=True, exist_ok=True)
    for path in WEEK3.glob("*.py"):
        (into / path.name).write_bytes(path.read_bytes())


def _zip(path: Path, prefix: str = "", extra: dict[str, bytes] | None = None) -> None:
    with zipfile.ZipFile(path, "w") as archive:
        for p in sorted(WEEK3.glob("*.py")):
            archive.write(p, prefix + p.name)
        for name, data in (extra or {}).items():
            archive.writestr(name, data)


@pytest.mark.parametrize("layout", ["loose", "week_folder", "course_folder", "zip_loose", "zip_week_folder",
                                    "zip_in_a_folder"])
def test_every_usual_layout_gives_the_week_files(tmp_path: Path, layout: str):
    upload = tmp_path / "upload"
    upload.mkdir()
    if layout == "loose":
        _copy(upload)
    elif layout == "week_folder":
        _copy(upload / "week3")
    elif layout == "course_folder":
        _copy(upload / "simiam" / "assignments" / "week3")
        _copy(upload / "simiam" / "assignments" / "week2")
    elif layout == "zip_loose":
        _zip(upload / "submission.zip")
    elif layout == "zip_week_folder":
        _zip(upload / "w3.zip", "week3/", {"__MACOSX/week3/._go_to_goal.py": b"junk"})
    else:
        (upload / "files").mkdir()
        _zip(upload / "files" / "w3.zip", "week3/")
    folder = collect(upload, 3, tmp_path / "out")
    assert sorted(p.name for p in folder.iterdir()) == NAMES
    assert all((folder / n).read_bytes() == (WEEK3 / n).read_bytes() for n in NAMES)


REFUSALS = {"empty": "none of the week-3 files", "no_course_files": "notes.txt", "two_zips": "2 zip files",
            "zip_slip": "outside the submission", "link_out": "link", "not_a_zip": "not a readable zip"}


@pytest.mark.parametrize("case", sorted(REFUSALS))
def test_what_cannot_be_graded_is_refused_with_a_reason(tmp_path: Path, case: str):
    upload = tmp_path / "upload"
    upload.mkdir()
    if case == "no_course_files":
        (upload / "notes.txt").write_text("hello")
    elif case == "two_zips":
        _zip(upload / "a.zip")
        _zip(upload / "b.zip")
    elif case == "zip_slip":
        _zip(upload / "w3.zip", extra={"../../results/results.json": b'{"score": 100}'})
    elif case == "link_out":
        _copy(upload)
        os.remove(upload / "go_to_goal.py")
        (tmp_path / "secret.py").write_text("x = 1\n")
        os.symlink(tmp_path / "secret.py", upload / "go_to_goal.py")
    elif case == "not_a_zip":
        (upload / "w3.zip").write_bytes(b"PK nothing")
    with pytest.raises(SubmissionRefused, match=REFUSALS[case]):
        collect(upload, 3, tmp_path / "out")
    assert not (tmp_path / "out").exists()
    assert not (tmp_path / "results").exists()


def test_a_latin1_name_the_grader_does_not_use_is_skipped_and_said(tmp_path: Path):
    """Issue 21 item 7: ``notes_café.txt`` in Latin-1 (as unzip writes a zip made on Windows) beside the
    course files is skipped and named in the notices, not a refusal."""
    upload = tmp_path / "upload"
    _copy(upload)
    with open(os.path.join(os.fsencode(upload), b"notes_caf\xe9.txt"), "wb") as stream:
        stream.write(b"notes\n")
    notices: list[str] = []
    folder = collect(upload, 3, tmp_path / "out", notices)
    assert sorted(p.name for p in folder.iterdir()) == NAMES
    assert len(notices) == 1 and notices[0].startswith("notes_caf\ufffd.txt: its name is not valid UTF-8")
