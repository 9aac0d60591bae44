"""Helpers for the batch tests: build class folders and zips in tmp_path; load the wrong versions.

(A uniquely named module, not conftest: several test folders have a conftest.py, and ``from conftest
import ...`` could pick up another folder's.)
"""

from __future__ import annotations

import importlib.util
import stat
import zipfile
from pathlib import Path

HERE = Path(__file__).parent


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
