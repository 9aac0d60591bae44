"""Open a student's ``.zip`` safely, in memory, without ever extracting it to disk.

A zip from 400 strangers is hostile input. Every entry is checked before one byte of it is read:

- its name stays inside the submission (no absolute path, drive letter, ``..`` component or NUL byte:
  "zip slip");
- it is a regular file (an entry whose Unix mode says symlink, device or fifo is refused; nothing is
  followed because nothing is extracted);
- it is not encrypted, and no two entries share a name;
- the sizes stay under the limits: per file, in total, in number of files, and in compression ratio
  (a "zip bomb" declares small sizes or packs gigabytes into kilobytes).

Declared sizes can lie, so reading stops at the limit whatever the header says. Anything refused raises
:class:`SubmissionRefused` with a reason an instructor (and the student) can act on.
"""

from __future__ import annotations

import io
import stat
import zipfile
import zlib
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from grader.batch.names import SubmissionRefused, check_path

# Path components that are never part of a submission (editor, OS and VCS litter). They are skipped
# unread, so they cost nothing and cannot trip the limits.
JUNK_PARTS = frozenset({"__MACOSX", "__pycache__", ".git", ".hg", ".svn", ".ipynb_checkpoints", ".venv",
                        "venv", ".idea", ".vscode", ".pytest_cache", ".mypy_cache", ".ruff_cache"})
JUNK_NAMES = frozenset({".DS_Store", "Thumbs.db", "desktop.ini"})


@dataclass(frozen=True)
class Limits:
    """Size limits for one submission (zip or folder). QuickBot submissions are a few dozen kB."""

    max_files: int = 500
    max_file_bytes: int = 5 * 1024 * 1024
    max_total_bytes: int = 20 * 1024 * 1024
    max_ratio: float = 100.0          # uncompressed / compressed, for entries above ratio_floor_bytes
    ratio_floor_bytes: int = 1024 * 1024


def is_junk(parts: tuple[str, ...]) -> bool:
    """True for OS/editor/VCS litter such as ``__MACOSX/`` or ``.DS_Store``."""
    return any(p in JUNK_PARTS for p in parts[:-1]) or (bool(parts) and
                                                         (parts[-1] in JUNK_NAMES or parts[-1] in JUNK_PARTS
                                                          or parts[-1].endswith(".pyc")
                                                          or parts[-1].startswith("._")))


def safe_member_path(name: str) -> tuple[str, ...]:
    """The path components of a zip entry name, or SubmissionRefused if it could escape the folder."""
    if "\x00" in name:
        raise SubmissionRefused(f"zip entry {name!r} has a NUL byte in its name")
    unified = name.replace("\\", "/")
    if unified.startswith("/") or (len(unified) > 1 and unified[1] == ":"):
        raise SubmissionRefused(f"zip entry {name!r} has an absolute path; zip the folder, not its location")
    parts = tuple(p for p in PurePosixPath(unified).parts if p not in ("", "."))
    if ".." in parts:
        raise SubmissionRefused(f"zip entry {name!r} points outside the submission ('..' in its path)")
    return parts


def entry_kind(info: zipfile.ZipInfo) -> str:
    """'dir', 'file', or the name of a forbidden special file type (from the Unix mode bits, if any)."""
    if info.is_dir():
        return "dir"
    kind = stat.S_IFMT(info.external_attr >> 16)
    if info.create_system != 3 or kind in (0, stat.S_IFREG):   # not Unix, or no type bits, or a file
        return "file"
    if kind == stat.S_IFDIR:
        return "dir"
    return "symlink" if kind == stat.S_IFLNK else "special file"


def read_zip(path: Path | bytes, limits: Limits | None = None, label: str = "") -> dict[str, bytes]:
    """Read every regular file of the zip at ``path`` (or in ``path``'s bytes: a zip the student uploaded
    inside a platform's download) into ``{relative/posix/path: bytes}``.

    Raises SubmissionRefused for a broken zip or any entry that breaks the rules in the module docstring.
    Junk entries (``__MACOSX/``, ``.DS_Store``, ``__pycache__``...) are skipped but still path-checked.
    """
    limits = limits or Limits()
    label = label or (path.name if isinstance(path, Path) else "the zip")
    try:
        archive = zipfile.ZipFile(io.BytesIO(path) if isinstance(path, bytes) else path)
    except (zipfile.BadZipFile, OSError, ValueError) as exc:
        raise SubmissionRefused(f"{label} is not a readable zip file ({exc})") from None
    files: dict[str, bytes] = {}
    total = 0
    with archive:
        infos = archive.infolist()
        for info in infos:
            parts = safe_member_path(info.filename)
            kind = entry_kind(info)
            if kind in ("symlink", "special file"):
                raise SubmissionRefused(f"zip entry {info.filename!r} is a {kind}; "
                                        f"only plain files are accepted")
            if kind == "dir" or not parts or is_junk(parts):
                continue
            check_path(parts)
            rel = "/".join(parts)
            if rel in files:
                raise SubmissionRefused(f"zip has two entries named {rel!r}")
            if len(files) >= limits.max_files:
                raise SubmissionRefused(f"zip has more than {limits.max_files} files")
            data = read_entry(archive, info, rel, limits, limits.max_total_bytes - total)
            total += len(data)
            files[rel] = data
    return files


def read_entry(archive: zipfile.ZipFile, info: zipfile.ZipInfo, rel: str, limits: Limits, room: int) -> bytes:
    """One entry's bytes, checked as :func:`read_zip` checks each (encryption, size per file, compression
    ratio) and read no further than ``room`` bytes whatever its header declares (SubmissionRefused)."""
    if info.flag_bits & 0x1:
        raise SubmissionRefused(f"zip entry {info.filename!r} is encrypted; submit it without a password")
    if info.file_size > limits.max_file_bytes:
        raise SubmissionRefused(f"{rel} is {info.file_size} bytes; the limit per file is "
                                f"{limits.max_file_bytes}")
    if (info.file_size > limits.ratio_floor_bytes
            and info.file_size > limits.max_ratio * max(info.compress_size, 1)):
        raise SubmissionRefused(f"{rel} compresses more than {limits.max_ratio:.0f}:1 (a zip bomb?)")
    return _read_capped(archive, info, rel, min(limits.max_file_bytes, room))


def _read_capped(archive: zipfile.ZipFile, info: zipfile.ZipInfo, rel: str, cap: int) -> bytes:
    """Read one entry, refusing it as soon as it grows past ``cap`` whatever its header declared."""
    chunks: list[bytes] = []
    size = 0
    try:
        with archive.open(info) as stream:
            while chunk := stream.read(64 * 1024):
                size += len(chunk)
                if size > cap:
                    raise SubmissionRefused(f"{rel} is larger than its header says, or the submission "
                                            f"is over the size limit")
                chunks.append(chunk)
    except (zipfile.BadZipFile, zlib.error, EOFError, OSError, NotImplementedError, RuntimeError) as exc:
        raise SubmissionRefused(f"zip entry {rel!r} cannot be read ({exc})") from None
    return b"".join(chunks)
