"""Every file simiam and the grader write in place: never through a link, never half-written, never at a name
someone else could guess first.

`grade week5` writes its report into `reports/` of the student's folder, the batch into an output folder,
`grade handout` next to the course: folders someone else may have prepared. A plain `open(path, "w")`
follows a link planted at `path` and overwrites whatever it points to; a temporary name such as
`.week5.zip.<pid>.tmp` can be guessed and planted too. So a file is written like this:

1. the folder it goes into is opened once, refusing a link there (O_DIRECTORY | O_NOFOLLOW); every step
   below works relative to that descriptor, so the folder cannot be swapped for a link half-way;
2. a link at the final name is refused (LinkRefused, an OSError that names the path);
3. the bytes go to a new temporary file with a random name in that folder, created exclusively
   (O_CREAT | O_EXCL | O_NOFOLLOW: never an existing file, never through a link), as tempfile.mkstemp does;
4. it is renamed over the final name (os.replace, which replaces a name and never follows a link there;
   a reader sees the old file or the new one, never a torn one). On any failure it is removed.

The folders above the one written into are the path the user gave and are followed as usual, unless the
caller names a folder `below` which none may be a link (the batch's output folder, grader.batch.store): then
every level from `below` down to the file is opened relative to the one above it with O_NOFOLLOW
(`open_folder_below`), so a link at any of them is refused, not followed. Writers
into a folder the grading made itself (tempfile.mkdtemp: the worker's copy of a submission, the spliced
files, a library being built) need none of this and use plain writes. Where the system has no O_NOFOLLOW
or descriptor-relative calls (Windows, where only `simiam run` and `simiam migrate` may run), the same
steps go by path: the links are refused as above, but one planted between the check and the write is not
seen (the rename still only replaces it).
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import BinaryIO

_TEMPORARY_SUFFIX = ".tmp"  # .<name>.<random>.tmp: what the batch sweeps up after a kill (grader.batch.store)
_AT_FOLDER = hasattr(os, "O_NOFOLLOW") and hasattr(os, "O_DIRECTORY") and os.open in os.supports_dir_fd


class LinkRefused(OSError):
    """A link where a file or the folder it goes into was to be written; nothing was written."""

    def __init__(self, path: Path) -> None:
        super().__init__(errno.ELOOP, f"{path} is a link, and nothing is written through a link", str(path))

    def __str__(self) -> str:
        return str(self.strerror)


def write_text(path: str | Path, text: str, *, encoding: str = "utf-8", errors: str = "strict",
               mode: int | None = None, fsync: bool = False, below: Path | None = None) -> Path:
    """Write `text` to `path` as above; `mode` sets the file's permission bits before a byte is written
    (a secret is never readable by others), `fsync` makes the bytes durable before the rename, `below` is
    a folder above `path` under which no level may be a link (see the module docstring)."""
    return write_bytes(path, text.encode(encoding, errors), mode=mode, fsync=fsync, below=below)


def write_bytes(path: str | Path, data: bytes, *, mode: int | None = None, fsync: bool = False,
                below: Path | None = None) -> Path:
    """Write `data` to `path` as above (see write_text for `mode`, `fsync` and `below`)."""
    with replacing(path, mode=mode, fsync=fsync, below=below) as stream:
        stream.write(data)
    return Path(path)


@contextlib.contextmanager
def replacing(path: str | Path, *, mode: int | None = None, fsync: bool = False,
              below: Path | None = None) -> Iterator[BinaryIO]:
    """A binary stream whose bytes become `path` when the block ends without an exception (for writers
    that stream: a zip, a CSV). If the block raises, `path` is left as it was."""
    path = Path(path)
    if not _AT_FOLDER:
        if below is not None:
            _refuse_links_by_path(below, path.parent)
        with _replacing_by_path(path, mode, fsync) as stream:
            yield stream
        return
    folder = _open_folder(path.parent) if below is None else open_folder_below(below, path.parent)
    try:
        _refuse_link(path, folder)
        temporary, fd = _create_temporary(path.name, folder, mode)
        try:
            with os.fdopen(fd, "wb") as stream:
                yield stream
                if fsync:
                    stream.flush()
                    os.fsync(stream.fileno())
            os.replace(temporary, path.name, src_dir_fd=folder, dst_dir_fd=folder)
        except BaseException:
            with contextlib.suppress(OSError):
                os.unlink(temporary, dir_fd=folder)
            raise
    finally:
        os.close(folder)


@contextlib.contextmanager
def _replacing_by_path(path: Path, mode: int | None, fsync: bool) -> Iterator[BinaryIO]:
    """`replacing` where descriptor-relative calls are missing: the same steps, by path."""
    path.parent.mkdir(parents=True, exist_ok=True)
    for checked in (path.parent, path):
        if checked.is_symlink():
            raise LinkRefused(checked)
    fd, temporary = tempfile.mkstemp(prefix=f".{path.name[:200]}.", suffix=_TEMPORARY_SUFFIX, dir=path.parent)
    try:
        if mode is not None:
            os.chmod(temporary, mode)
        with os.fdopen(fd, "wb") as stream:
            yield stream
            if fsync:
                stream.flush()
                os.fsync(stream.fileno())
        os.replace(temporary, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise


def _open_folder(path: Path) -> int:
    """A descriptor of folder `path`, created if missing (its parents as usual), never through a link at
    `path` itself. The caller closes it."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with contextlib.suppress(FileExistsError):  # a link there (even dangling) is found just below
        os.mkdir(path)
    try:
        return os.open(path, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError as exc:
        if exc.errno == errno.ELOOP or (exc.errno == errno.ENOTDIR and path.is_symlink()):
            raise LinkRefused(path) from None
        raise


def open_folder_below(root: Path, folder: Path, create: bool = True) -> int:
    """A descriptor of `folder`, which is `root` or lies below it: `root` is opened as the user gave it,
    every level below it relative to the one above with O_NOFOLLOW (and made first when missing, if
    `create`), so a link at any level below `root` is LinkRefused naming it, and none can be swapped in
    half-way. FileNotFoundError when a level is missing and not `create`. The caller closes it."""
    parts = folder.relative_to(root).parts     # ValueError when `folder` is not below `root`
    if any(part in (".", "..") for part in parts):
        raise ValueError(f"{folder} names a folder above {root}")
    if create:
        root.mkdir(parents=True, exist_ok=True)
    fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    here = root
    try:
        for part in parts:
            here = here / part
            if create:
                with contextlib.suppress(FileExistsError):
                    os.mkdir(part, dir_fd=fd)
            try:
                inner = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=fd)
            except OSError as exc:
                if exc.errno == errno.ELOOP or (exc.errno == errno.ENOTDIR and _is_link(part, fd)):
                    raise LinkRefused(here) from None
                raise
            os.close(fd)
            fd = inner
    except BaseException:
        os.close(fd)
        raise
    return fd


def _is_link(name: str, folder: int) -> bool:
    try:
        return stat.S_ISLNK(os.stat(name, dir_fd=folder, follow_symlinks=False).st_mode)
    except OSError:
        return False


def _refuse_links_by_path(root: Path, folder: Path) -> None:
    """`open_folder_below`'s refusal where descriptor-relative calls are missing: by path."""
    here = root
    for part in folder.relative_to(root).parts:
        here = here / part
        if here.is_symlink():
            raise LinkRefused(here)


def _refuse_link(path: Path, folder: int) -> None:
    try:
        info = os.stat(path.name, dir_fd=folder, follow_symlinks=False)
    except FileNotFoundError:
        return
    if stat.S_ISLNK(info.st_mode):
        raise LinkRefused(path)


def _create_temporary(name: str, folder: int, mode: int | None) -> tuple[str, int]:
    """(name, descriptor) of a new file in `folder` that did not exist before and is not a link: a name
    nobody can predict, created with O_EXCL (a name taken, by chance or on purpose, is drawn again)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
    for _ in range(100):
        temporary = f".{name[:200]}.{secrets.token_hex(8)}{_TEMPORARY_SUFFIX}"
        try:
            fd = os.open(temporary, flags, 0o600 if mode is not None else 0o666, dir_fd=folder)
        except FileExistsError:
            continue
        if mode is not None:  # exactly these bits, whatever the umask (0o755 for a script)
            try:
                os.fchmod(fd, mode)
            except BaseException:
                os.close(fd)
                os.unlink(temporary, dir_fd=folder)
                raise
        return temporary, fd
    raise FileExistsError(errno.EEXIST, "no free temporary name", name)
