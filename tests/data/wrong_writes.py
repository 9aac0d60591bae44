"""WRONG VERSIONS (tests/grader/test_link_writes.py): how the trusted side wrote files before issue 22.
Each follows a link planted at its final name or at its temporary name, and so overwrites whatever the link
points to; the static walk of that test finds each of them too."""

from __future__ import annotations

import json
import os
import zipfile
from pathlib import Path


def write_atomic(path: Path, text: str) -> None:
    """The batch store's write: a temporary name anyone can predict (the pid), opened as it is."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    with open(tmp, "w", encoding="utf-8", errors="replace") as stream:
        stream.write(text)
    os.replace(tmp, path)


def write_zip(path: Path, files: dict[str, bytes]) -> Path:
    """`grade handout`'s zip: the same predictable temporary name."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as archive:
        for name in sorted(files):
            archive.writestr(name, files[name])
    os.replace(tmp, path)
    return path


def write_outputs(result: dict, out_dir: Path) -> Path:
    """`grade`'s weekN.json in the student's reports/: written through whatever is there."""
    out_dir.mkdir(parents=True, exist_ok=True)
    json_path = out_dir / f"week{result['week']}.json"
    json_path.write_text(json.dumps(result, indent=1), encoding="utf-8")
    return json_path
