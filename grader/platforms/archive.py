"""Write the zips an instructor uploads or hands out: same bytes for the same content, never half-written.

Entries get a fixed timestamp and explicit Unix modes (scripts 0755, secrets 0600, the rest 0644), so
rebuilding an unchanged week gives an identical zip and the platform sees executable scripts whatever the
instructor's umask. The zip is written next to its final name and moved into place (simiam.safe_write: a
temporary name nobody can predict, never through a link).
"""

from __future__ import annotations

import zipfile
from pathlib import Path

from grader.batch.windows_names import problem
from simiam import safe_write

_EPOCH = (2014, 1, 1, 0, 0, 0)   # the course's first run; zip cannot store dates before 1980


def write_zip(path: Path, files: dict[str, bytes], modes: dict[str, int] | None = None) -> Path:
    """Write `files` ({posix path inside the zip: bytes}) to `path`, each with mode 0644 unless `modes`
    names another (0o755 for scripts, 0o600 for what only the owner may read)."""
    modes = modes or {}
    for name in files:  # checked before anything is written: a zip unpacked on Windows must mean the same
        _check_entry(name)
    with safe_write.replacing(path) as stream, zipfile.ZipFile(stream, "w", zipfile.ZIP_DEFLATED) as archive:
        for name in sorted(files):
            info = zipfile.ZipInfo(name, _EPOCH)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.create_system = 3                      # Unix, so that the mode bits below are honoured
            info.external_attr = (0o100000 | modes.get(name, 0o644)) << 16
            archive.writestr(info, files[name])
    return path


def _check_entry(name: str) -> None:
    """Refuse an entry name that would unpack differently on Windows: a backslash (a folder there, part of
    the name elsewhere; what str() of a Windows path gives), an absolute or drive path, or a component
    Windows cannot store (grader.batch.windows_names: `aux.py`, `week3.`). Our own names: a bug, not input."""
    parts = name.split("/")
    if "\\" in name or name.startswith("/") or ":" in parts[0] or "" in parts or ".." in parts:
        raise ValueError(f"zip entry {name!r}: use a relative path with '/' between folders")
    for part in parts:
        why = problem(part)
        if why:
            raise ValueError(f"zip entry {name!r}: {part!r} {why}")
