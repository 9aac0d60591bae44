"""Helpers for the batch tests: build class folders and zips in tmp_path; load the wrong versions.

(A uniquely named module, not conftest: several test folders have a conftest.py, and ``from conftest
import ...`` could pick up another folder's.)
"""

from __future__ import annotations

import importlib.util
import os
import stat
import zipfile
from pathlib import Path

HERE = Path(__file__).parent
# The wall budget of a batch test in which one submission must run out of time while another must finish:
# a fake grading takes milliseconds, but the budget also covers starting (or restarting) the grading
# process, 0.05 s of CPU yet up to 0.6 s of wall time with both cores busy (the slowest finishing task of
# these tests took 0.28 s with eight busy loops on two cores, against budgets of 1.5 to 3 s before). Six
# seconds is ten times the worst; a test pays it once for each submission it lets hang.
HANG_BUDGET_S = 6.0


def load_wrong() -> object:
    """tests/data/batch/wrong_batch.py as a module."""
    path = HERE.parent / "data" / "batch" / "wrong_batch.py"
    spec = importlib.util.spec_from_file_location("wrong_batch", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def make_zip(path: Path, entries: dict[str, bytes | str], symlinks: dict[str, str] | None = None) -> Path:
    """A zip with the given files (and Unix symlink entries) written exactly as named."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in entries.items():
            archive.writestr(name, data)
        for name, target in (symlinks or {}).items():
            info = zipfile.ZipInfo(name)
            info.create_system = 3
            info.external_attr = (stat.S_IFLNK | 0o777) << 16
            archive.writestr(info, target)
    return path


def make_class(root: Path, answers: dict[str, str], zipped: tuple[str, ...] = ()) -> Path:
    """A class folder: one folder (or zip, for ids in ``zipped``) per student with ``answer.txt``."""
    root.mkdir(parents=True, exist_ok=True)
    for sid, answer in answers.items():
        if sid in zipped:
            make_zip(root / f"{sid}.zip", {f"{sid}/answer.txt": answer + "\n"})
        else:
            (root / sid).mkdir()
            (root / sid / "answer.txt").write_text(answer + "\n")
    return root


def _deep_folder(folder: Path, depth: int) -> None:
    """``folder/d/d/.../d`` ``depth`` levels deep, made relative to an open descriptor (the full path is
    longer than PATH_MAX, as a student's zip extracted by hand could make it)."""
    fd = os.open(folder, os.O_RDONLY)
    for _ in range(depth):
        os.mkdir("d", dir_fd=fd)
        child = os.open("d", os.O_RDONLY, dir_fd=fd)
        os.close(fd)
        fd = child
    os.close(fd)


def hostile(klass: Path, case: str) -> str:
    """Add one hostile entry to the class folder; returns the id it is stored under in batch.json."""
    if case == "id_255_bytes":
        sid = "a" * 255
        (klass / sid).mkdir()
        (klass / sid / "answer.txt").write_text("score 10\n")
        return sid
    if case == "id_not_utf8":
        folder = os.path.join(os.fsencode(klass), b"caf\xe9")
        os.mkdir(folder)
        Path(os.fsdecode(folder), "answer.txt").write_text("score 10\n")
        return os.fsdecode(b"caf\xe9")
    if case == "id_control_chars":
        sid = "evil\x1b[2J\x07"
        (klass / sid).mkdir()
        (klass / sid / "answer.txt").write_text("score 10\n")
        return sid
    if case == "symlink_loop":
        (klass / "loop").mkdir()
        (klass / "loop" / "answer.txt").write_text("score 10\n")
        os.symlink("x", klass / "loop" / "x")
        return "loop"
    if case == "nested_1000":
        (klass / "deep").mkdir()
        (klass / "deep" / "answer.txt").write_text("score 10\n")
        _deep_folder(klass / "deep", 1000)
        return "deep"
    zips = {"zip_file_and_folder": {"answer.txt": "score 10", "go_to_goal.py": "x", "go_to_goal.py/a": "y"},
            "zip_case_twins": {"answer.txt": "score 10", "Go_To_Goal.py": "x", "go_to_goal.py": "y"},
            "zip_long_name": {"answer.txt": "score 10", "n" * 300 + ".py": "x"},
            "zip_deep": {"answer.txt": "score 10", "d/" * 2000 + "x.py": "x"}}
    make_zip(klass / f"{case}.zip", zips[case])
    return case


CASES = ["id_255_bytes", "id_not_utf8", "id_control_chars", "symlink_loop", "nested_1000",
         "zip_file_and_folder", "zip_case_twins", "zip_long_name", "zip_deep"]


def remove_deep_chain(folder: Path) -> None:
    """Remove ``folder/d/d/...`` without recursion: pull each inner ``d`` up one level, then drop it."""
    while (folder / "d").is_dir():
        os.rename(folder / "d", folder / "d_up")
        if (folder / "d_up" / "d").is_dir():
            os.rename(folder / "d_up" / "d", folder / "d")
        os.rmdir(folder / "d_up")


class StopAfterOne:
    """An executor stopped (Ctrl-C) right after its first student: the rest keep their older results
    (an interrupted regrade)."""

    def describe(self) -> dict:
        return {"executor": "stop-after-one"}

    def run(self, grade_fn, tasks, on_done) -> None:
        import batch_fake_grader

        task = next(iter(tasks))
        on_done(task, {"status": "ok", "value": batch_fake_grader.fake_grade(task), "seconds": 0.0})
        raise KeyboardInterrupt
