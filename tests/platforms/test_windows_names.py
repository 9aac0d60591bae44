"""Issue 23: Windows-style names wherever student folders, zips and names are handled: backslashes and drive
letters in zips, names Windows takes for one file (case, trailing dots and spaces), device names (CON,
aux.py), and the week-folder rule of the command line in any case. Each would break or mislead a grader
that writes the files on Windows (a device opened instead of a file, one file over another)."""

from __future__ import annotations

import zipfile
from pathlib import Path

import pytest
from mistakes import ROOT

from grader.batch.names import SubmissionRefused as Refused
from grader.batch.names import check_paths
from grader.batch.windows_names import leave_out, problem, same_file_key
from grader.platforms.intake import SubmissionRefused, collect
from simiam.course.folders import default_week_folder

WEEK3 = ROOT / "solutions" / "week3"
NAMES = sorted(p.name for p in WEEK3.glob("*.py"))


def _zip(path: Path, names: dict[str, str], extra: dict[str, bytes] | None = None) -> None:
    """A zip whose entry for each course file is `names[file]` (a Windows zipper may write backslashes)."""
    with zipfile.ZipFile(path, "w") as archive:
        for p in sorted(WEEK3.glob("*.py")):
            archive.writestr(names.get(p.name, p.name), p.read_bytes())
        for name, data in (extra or {}).items():
            archive.writestr(name, data)


def test_a_zip_with_backslash_paths_gives_the_week_files(tmp_path: Path) -> None:
    upload = tmp_path / "upload"
    upload.mkdir()
    _zip(upload / "week3.zip", {n: f"week3\\{n}" for n in NAMES})
    folder = collect(upload, 3, tmp_path / "out")
    assert sorted(p.name for p in folder.iterdir()) == NAMES
    assert all((folder / n).read_bytes() == (WEEK3 / n).read_bytes() for n in NAMES)


@pytest.mark.parametrize("entry, words", [
    ("C:\\Users\\ana\\week3\\go_to_goal.py", "absolute path"),
    ("c:go_to_goal.py", "absolute path"),                 # drive-relative: still names a drive
    ("\\\\server\\share\\go_to_goal.py", "absolute path"),  # a UNC path
    ("week3\\..\\..\\go_to_goal.py", "outside the submission"),
])
def test_windows_absolute_and_escaping_zip_entries_are_refused(tmp_path: Path, entry: str, words: str
                                                                ) -> None:
    upload = tmp_path / "upload"
    upload.mkdir()
    _zip(upload / "week3.zip", {"go_to_goal.py": entry})
    with pytest.raises(SubmissionRefused, match=words):
        collect(upload, 3, tmp_path / "out")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("other", ["GO_TO_GOAL.PY", "Go_To_Goal.py"])
def test_names_that_differ_only_by_case_are_refused(tmp_path: Path, other: str) -> None:
    """On Windows (and macOS) one would overwrite the other: which one the student meant is unknowable."""
    upload = tmp_path / "upload"
    upload.mkdir()
    _zip(upload / "week3.zip", {}, {other: b"x = 1\n"})
    with pytest.raises(SubmissionRefused, match="differ only by case"):
        collect(upload, 3, tmp_path / "out")


LEFT_OUT = {"CON": "device name", "aux.py": "device name", "nul.txt": "device name",
            "Com1.log": "device name", "go_to_goal.py.": "dot or a space", "notes.txt ": "dot or a space",
            "what?.py": "does not allow"}


def test_names_windows_cannot_store_are_left_out_and_said(tmp_path: Path) -> None:
    """`go_to_goal.py.` would become go_to_goal.py on Windows, over the real one; `aux.py` a device."""
    upload = tmp_path / "upload"
    upload.mkdir()
    for p in WEEK3.glob("*.py"):
        (upload / p.name).write_bytes(p.read_bytes())
    for name in LEFT_OUT:
        (upload / name).write_text("while True: pass\n")
    notices: list[str] = []
    folder = collect(upload, 3, tmp_path / "out", notices)
    assert sorted(p.name for p in folder.iterdir()) == NAMES
    assert (folder / "go_to_goal.py").read_bytes() == (WEEK3 / "go_to_goal.py").read_bytes()
    assert len(notices) == len(LEFT_OUT)
    for name, words in LEFT_OUT.items():
        note = next(n for n in notices if n.startswith(f"{name}: "))
        assert words in note and note.endswith("it was left out")


def test_a_course_file_in_a_folder_windows_cannot_store_is_left_out_too(tmp_path: Path) -> None:
    upload = tmp_path / "upload"
    upload.mkdir()
    _zip(upload / "w.zip", {n: f"week3./{n}" for n in NAMES}, {"week3/go_to_goal.py": b"x = 1\n"})
    notices: list[str] = []
    folder = collect(upload, 3, tmp_path / "out", notices)
    assert sorted(p.name for p in folder.iterdir()) == ["go_to_goal.py"]
    assert sum("week3./" in n for n in notices) == len(NAMES)


@pytest.mark.parametrize("name, fine", [
    ("go_to_goal.py", True), ("console.py", True), ("con_notes.txt", True), ("com10", True), ("lpt", True),
    ("CON", False), ("con.tar.gz", False), ("LPT9.py", False), ("aux .py", False), ("a.", False),
    ("a ", False), ("a:b", False), ("a|b", False), ("a\\b", False), ("a*b", False), ('a"b', False),
])
def test_what_windows_cannot_store(name: str, fine: bool) -> None:
    assert (problem(name) is None) == fine


def test_windows_same_file_key_and_the_batch_clash_check() -> None:
    assert same_file_key("Week3/Go_To_Goal.py. ") == same_file_key("week3/go_to_goal.py")
    assert same_file_key("week3/a.py") != same_file_key("week3/b.py")
    with pytest.raises(Refused, match="trailing dot or space"):
        check_paths(["week3/go_to_goal.py", "week3 /go_to_goal.py"])
    kept = leave_out({"a.py": b"", "aux.py": b"", "sub/CON/b.py": b""}, notes := [])
    assert list(kept) == ["a.py"] and len(notes) == 2


def test_the_week_folder_rule_takes_the_current_folder_in_any_case(tmp_path: Path) -> None:
    """Windows keeps `Week3` as the student typed it, and takes it for week3."""
    folder = tmp_path / "Week3"
    folder.mkdir()
    assert default_week_folder(3, folder) == folder


@pytest.mark.parametrize("entry", ["week3\\go_to_goal.py", "C:/week3/go_to_goal.py", "/week3/a.py",
                                   "week3/aux.py", "week3./a.py", "week3//a.py", "week3/../a.py"])
def test_the_zips_the_grader_writes_take_no_name_that_unpacks_differently_on_windows(tmp_path: Path,
                                                                                      entry: str) -> None:
    from grader.platforms.archive import write_zip

    with pytest.raises(ValueError, match="zip entry"):
        write_zip(tmp_path / "w.zip", {"week3/go_to_goal.py": b"", entry: b""})
    assert not (tmp_path / "w.zip").exists()
    write_zip(tmp_path / "w.zip", {"week3/go_to_goal.py": b"x", "setup.sh": b"y"})
    assert zipfile.ZipFile(tmp_path / "w.zip").namelist() == ["setup.sh", "week3/go_to_goal.py"]


def test_migrate_finds_last_weeks_folder_named_in_any_case(tmp_path: Path, monkeypatch) -> None:
    """`simiam migrate week4 --from WEEK3` (Windows users type names in any case) finds ./week3."""
    from simiam.course.migrate import _source_folder

    (tmp_path / "week3").mkdir()
    monkeypatch.chdir(tmp_path)
    assert _source_folder("WEEK3", 3).resolve() == (tmp_path / "week3").resolve()
