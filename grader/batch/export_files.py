"""A course platform's download as it comes, a ``.zip`` or the folder it was extracted to, listed and
read without extracting it and without following any link.

The whole export is hostile input, as each student's zip is (grader/batch/zips.py): every name is checked
before it is used (no absolute path, ``..`` or NUL: "zip slip"), links and special files are listed as
such and never read, and the number of entries and the bytes read are capped for the whole export, on
top of each student's own limits (:class:`grader.batch.zips.Limits`), which :func:`read_members` applies.
An entry whose name cannot be used at all is kept in :attr:`Export.problems` for the instructor.
"""

from __future__ import annotations

import dataclasses
import os
import stat
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

from grader.batch.names import MAX_DEPTH, SubmissionRefused, shown
from grader.batch.zips import Limits, entry_kind, is_junk, read_entry, safe_member_path

EXTRA_DEPTH = 3  # folders of the export itself above a student's files (Moodle: one)


@dataclass(frozen=True)
class ExportLimits:
    """Caps for a whole export (each student's files also have :class:`Limits`)."""

    max_entries: int = 200_000
    max_total_bytes: int = 8 * 1024**3  # declared in the zip, or on disk, for the whole export
    max_metadata_bytes: int = 32 * 1024**2  # submission_metadata.yml, a roster, a times file


@dataclass(frozen=True)
class Entry:
    """One file of the export: its path inside it (``/``-separated, checked) and what it is."""

    name: str
    size: int
    link: bool = False  # a link or special file: listed so it is reported, never read
    local_time: tuple[int, ...] = ()  # a zip entry's date and time, local to whoever zipped it
    mtime: float = 0.0  # a file's modification time (an extracted folder)


@dataclass
class Export:
    """The listing of an export; ``path`` is the zip or the folder."""

    path: Path
    is_zip: bool
    entries: list[Entry] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)  # names that could not be placed at all
    _index: dict[str, Entry] | None = field(default=None, repr=False)
    prefix: str = ""  # a zip whose entries all sit in one folder: that folder, stepped into

    def entry(self, name: str) -> Entry | None:
        """The entry named ``name`` (an index built once: 400 students of a large export read in turn)."""
        if self._index is None or len(self._index) != len(self.entries):
            self._index = {e.name: e for e in self.entries}
        return self._index.get(name)

    def step_into(self, folder: str) -> None:
        """Read the export from inside ``folder`` (a zip whose entries all sit in it)."""
        prefix = folder + "/"
        self.entries = [dataclasses.replace(e, name=e.name[len(prefix):]) for e in self.entries
                        if e.name.startswith(prefix)]
        self.prefix, self._index = self.prefix + prefix, None

    def top_names(self) -> list[str]:
        """The first path components, sorted, each once."""
        return sorted({e.name.split("/", 1)[0] for e in self.entries})


class ExportRefused(Exception):
    """The export cannot be read at all (the batch stops with exit status 2 and this reason)."""


def list_export(path: Path, limits: ExportLimits | None = None) -> Export:
    """List every file of the export at ``path`` (ExportRefused when it is unreadable or over its caps)."""
    limits = limits or ExportLimits()
    export = Export(path, is_zip=path.is_file())
    if export.is_zip:
        _list_zip(export, limits)
    else:
        _list_folder(export, limits)
    if sum(e.size for e in export.entries) > limits.max_total_bytes:
        raise ExportRefused(f"{path.name} holds more than {limits.max_total_bytes} bytes; split the class")
    return export


def _list_zip(export: Export, limits: ExportLimits) -> None:
    try:
        with zipfile.ZipFile(export.path) as archive:
            infos = archive.infolist()
    except (zipfile.BadZipFile, OSError, ValueError) as exc:
        raise ExportRefused(f"{export.path.name} is not a readable zip file ({exc})") from None
    if len(infos) > limits.max_entries:
        raise ExportRefused(f"{export.path.name} has {len(infos)} entries; at most {limits.max_entries}")
    for info in infos:
        try:
            parts = safe_member_path(info.filename)
        except SubmissionRefused as refused:
            export.problems.append(shown(str(refused)))
            continue
        kind = entry_kind(info)
        if kind == "dir" or not parts or is_junk(parts):
            continue
        export.entries.append(Entry("/".join(parts), max(0, info.file_size), link=kind != "file",
                                    local_time=tuple(info.date_time)))


def _list_folder(export: Export, limits: ExportLimits) -> None:
    root = export.path
    for dirpath, dirnames, filenames in os.walk(root, followlinks=False, onerror=_walk_error):
        here = Path(dirpath)
        parts = here.relative_to(root).parts
        for name in sorted(dirnames):
            if (here / name).is_symlink() or is_junk((*parts, name, "x")):
                dirnames.remove(name)
                if (here / name).is_symlink():
                    export.entries.append(Entry("/".join((*parts, name)), 0, link=True))
        if len(parts) >= MAX_DEPTH + EXTRA_DEPTH and dirnames:
            export.problems.append(
                f"{shown('/'.join(parts))[:200]}/... is nested more than "
                f"{MAX_DEPTH + EXTRA_DEPTH} folders deep; not read"
            )
            dirnames.clear()
        for name in sorted(filenames):
            rel = (*parts, name)
            if is_junk(rel):
                continue
            if len(export.entries) >= limits.max_entries:
                raise ExportRefused(f"{root.name} has more than {limits.max_entries} files")
            try:
                info = os.lstat(here / name)
            except OSError as exc:
                export.problems.append(f"{shown('/'.join(rel))}: cannot be read ({exc.strerror})")
                continue
            regular = stat.S_ISREG(info.st_mode)
            export.entries.append(Entry("/".join(rel), info.st_size if regular else 0, link=not regular,
                                        mtime=info.st_mtime))


def _walk_error(exc: OSError) -> None:
    raise ExportRefused(f"a folder of the export cannot be read ({exc})")


def read_members(export: Export, members: list[tuple[str, str]], limits: Limits) -> dict[str, bytes]:
    """``{path in the submission: bytes}`` for one student's ``(name in the export, path)`` pairs, within
    the student's limits (SubmissionRefused). A link or special file is refused, never followed."""
    files: dict[str, bytes] = {}
    if len(members) > limits.max_files:
        raise SubmissionRefused(f"the submission has more than {limits.max_files} files")
    total = 0
    archive = zipfile.ZipFile(export.path) if export.is_zip else None
    try:
        for name, rel in members:
            entry = export.entry(name)
            if entry is None or entry.link:
                raise SubmissionRefused(
                    f"{shown(name)} is a link or a special file; only plain files are "
                    f"read (links are never followed)"
                )
            room = limits.max_total_bytes - total
            data = (
                read_entry(archive, archive.getinfo(export.prefix + name), rel, limits, room)
                if archive is not None
                else _read_file(export.path, name, rel, min(limits.max_file_bytes, room))
            )
            total += len(data)
            files[rel] = data
    except (zipfile.BadZipFile, KeyError) as exc:
        raise SubmissionRefused(f"the export's entry cannot be read ({exc})") from None
    finally:
        if archive is not None:
            archive.close()
    return files


def _read_file(root: Path, name: str, rel: str, cap: int) -> bytes:
    """A file of an export folder, opened without following a link in its last component and refused
    when it is not regular or grows past ``cap`` (its folders were walked without following links)."""
    flags = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(root.joinpath(*name.split("/")), flags)
    except OSError as exc:
        raise SubmissionRefused(f"{shown(rel)} cannot be read ({exc.strerror}; a link?)") from None
    with os.fdopen(fd, "rb") as stream:
        if not stat.S_ISREG(os.fstat(stream.fileno()).st_mode):
            raise SubmissionRefused(f"{shown(rel)} is not a regular file")
        data = stream.read(cap + 1)
    if len(data) > cap:
        raise SubmissionRefused(f"{shown(rel)} is over the size limit ({cap} bytes left for it)")
    return data


def read_metadata(export: Export, name: str, limits: ExportLimits | None = None) -> bytes:
    """A metadata file of the export (Gradescope's ``submission_metadata.yml``), capped (ExportRefused)."""
    cap = (limits or ExportLimits()).max_metadata_bytes
    big = Limits(max_files=1, max_file_bytes=cap, max_total_bytes=cap, max_ratio=1000.0)
    try:
        return read_members(export, [(name, name)], big)[name]
    except SubmissionRefused as refused:
        raise ExportRefused(f"{name}: {refused}") from None
