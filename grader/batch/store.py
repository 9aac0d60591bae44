"""The output folder of a batch: file names, atomic writes, and one writer at a time.

Every file is written through simiam.safe_write (a random temporary name in the same folder, created
exclusively, moved into place with ``os.replace``; never through a link), so a batch killed at any instant
leaves each file either complete or absent. A student's HTML is written before their JSON: the JSON is the
commit record the resume logic trusts.

Nothing under the output folder is written, moved or deleted through a link, at any level (issue 30 item
5: a ``gradescope/`` or ``superseded/`` swapped for a link to an outside folder once had results written,
folders moved and files deleted outside ``--out``). While a batch holds the folder (``exclusive``), or
inside ``output_folder(out)``, every function here that is given a path below ``out`` opens each level
below ``out`` relative to the one above it with O_NOFOLLOW (simiam.safe_write.open_folder_below), so a link
at any level is refused with an OSError naming it (safe_write.LinkRefused; the batch stops and says
so) rather than followed. Outside an output folder (a platform's entrypoint writing its one file) only the
last folder is checked, as safe_write does. The writers under ``--out``:

- ``write_atomic(path, text)`` / ``write_json(path, value)``: a file, its folders made as needed;
- ``make_folder(path)``: a folder and the ones above it (below ``out``);
- ``move(src, dst)``: a file or folder to another place under ``out``, replacing what is there (a folder
  there is removed first, without following any link inside it); False when ``src`` is absent;
- ``remove(path)``: a file, a link (the link itself) or a whole folder; False when absent;
- ``entries(folder)``: the names in a folder below ``out`` and whether each is a real folder (never a link).
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
import secrets
import stat
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import BinaryIO, TextIO

from simiam import safe_write

LOCK = ".batch.lock"
SEED = ".seed"         # the folder's secret seed (see :func:`folder_seed`)


class OutputBusy(Exception):
    """Another batch is writing to the same output folder."""


_roots: dict[Path, int] = {}   # the output folders held now (exclusive, output_folder), with how often
_roots_lock = threading.Lock()


@contextlib.contextmanager
def output_folder(out: Path) -> Iterator[Path]:
    """While inside, no level below ``out`` is followed if it is a link, in any function of this module
    (see the module docstring). Nests; ``exclusive`` enters it for the whole run. Yields ``out``."""
    for root in {Path(out), Path(out).absolute()}:
        with _roots_lock:
            _roots[root] = _roots.get(root, 0) + 1
    try:
        yield Path(out)
    finally:
        for root in {Path(out), Path(out).absolute()}:
            with _roots_lock:
                _roots[root] -= 1
                if not _roots[root]:
                    del _roots[root]


def _root_of(path: Path) -> Path | None:
    """The held output folder ``path`` lies below (the outermost, so that every level below it is checked),
    or None."""
    with _roots_lock:
        roots = sorted(_roots, key=lambda r: len(r.parts))
    for candidate in (path, path.absolute()):
        for root in roots:
            if candidate != root and candidate.is_relative_to(root):
                return root
    return None


def _folder(path: Path, create: bool = True) -> int:
    """A descriptor of the folder ``path``: below a held output folder every level is checked for links;
    elsewhere only ``path`` itself. The caller closes it."""
    root = _root_of(path)
    if root is not None:
        return safe_write.open_folder_below(root, path, create=create)
    if create:
        path.mkdir(parents=True, exist_ok=True)
    try:
        return os.open(path, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError as exc:
        if exc.errno == errno.ELOOP or (exc.errno == errno.ENOTDIR and path.is_symlink()):
            raise safe_write.LinkRefused(path) from None
        raise


def write_atomic(path: Path, text: str, mode: int | None = None) -> None:
    """Write ``text`` to ``path`` so that readers see the old file or the new one, never a torn one.

    A lone surrogate (a student's non-UTF-8 file name, or text their code sent) is written as ``?``
    rather than failing the write: nothing a student sends can stop a file from being written."""
    safe_write.write_text(path, text, errors="replace", mode=mode, fsync=True, below=_root_of(Path(path)))


def make_folder(path: Path) -> None:
    """``path`` and the folders above it made as needed; a link at any level below the output folder is
    refused (LinkRefused), never followed."""
    os.close(_folder(Path(path)))


def _lstat(name: str, folder: int) -> os.stat_result | None:
    try:
        return os.stat(name, dir_fd=folder, follow_symlinks=False)
    except FileNotFoundError:
        return None


def _remove_tree_at(name: str, folder: int) -> None:
    """shutil.rmtree(name, dir_fd=folder) as Python 3.10 lacks it: every level opened with O_NOFOLLOW, so a
    link swapped in for a sub-folder is removed itself, never entered."""
    fd = os.open(name, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=folder)
    try:
        for entry in list(os.scandir(fd)):
            if entry.is_dir(follow_symlinks=False):
                _remove_tree_at(entry.name, fd)
            else:
                os.unlink(entry.name, dir_fd=fd)
    finally:
        os.close(fd)
    os.rmdir(name, dir_fd=folder)


def _remove_at(name: str, folder: int, info: os.stat_result) -> None:
    if stat.S_ISDIR(info.st_mode):   # a real folder: removed descriptor-relative, links inside not followed
        _remove_tree_at(name, folder)
    else:                            # a file, or a link itself (never what it points to)
        os.unlink(name, dir_fd=folder)


def remove(path: Path) -> bool:
    """Remove the file, link or folder at ``path`` (a folder with all it holds, following no link); False
    when nothing is there (or a folder above it is missing)."""
    path = Path(path)
    try:
        folder = _folder(path.parent, create=False)
    except FileNotFoundError:
        return False
    try:
        info = _lstat(path.name, folder)
        if info is None:
            return False
        _remove_at(path.name, folder, info)
        return True
    finally:
        os.close(folder)


def move(src: Path, dst: Path) -> bool:
    """Move the file or folder at ``src`` to ``dst`` (its folders made as needed), replacing a file or
    folder there; a link at ``src`` is moved as the link itself. False when nothing is at ``src``."""
    src, dst = Path(src), Path(dst)
    try:
        source = _folder(src.parent, create=False)
    except FileNotFoundError:
        return False
    try:
        if _lstat(src.name, source) is None:
            return False
        target = _folder(dst.parent)
        try:
            there = _lstat(dst.name, target)
            if there is not None:
                _remove_at(dst.name, target, there)
            os.replace(src.name, dst.name, src_dir_fd=source, dst_dir_fd=target)
        finally:
            os.close(target)
        return True
    finally:
        os.close(source)


def entries(folder: Path) -> list[tuple[str, bool]]:
    """(name, is a real folder) of each entry of ``folder``, sorted; [] when it is missing. A link is
    listed as what it is (not a folder), never followed."""
    try:
        fd = _folder(Path(folder), create=False)
    except FileNotFoundError:
        return []
    try:
        return sorted((entry.name, entry.is_dir(follow_symlinks=False)) for entry in os.scandir(fd))
    finally:
        os.close(fd)


def write_bytes_atomic(path: Path, data: bytes, mode: int | None = None) -> None:
    """Write ``data`` (a zip of feedback files) to ``path`` as :func:`write_atomic` writes text."""
    safe_write.write_bytes(path, data, mode=mode, fsync=True, below=_root_of(Path(path)))


@contextlib.contextmanager
def replacing(path: Path) -> Iterator[BinaryIO]:
    """A binary stream whose bytes replace ``path`` atomically when the block ends (nothing is left if it
    raises): a zip of feedback files written as it is built, never whole in memory."""
    with safe_write.replacing(path, fsync=True, below=_root_of(Path(path))) as stream:
        yield stream


def write_json(path: Path, value: object, mode: int | None = None) -> None:
    """Atomically write ``value`` as indented, key-sorted JSON (stable bytes for stable results)."""
    write_atomic(path, json.dumps(value, indent=2, sort_keys=True, allow_nan=False) + "\n", mode)


def read_json(path: Path) -> dict | None:
    """A stored result, or None if it is missing or unreadable (then it is simply graded again)."""
    try:
        value = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return value if isinstance(value, dict) else None


@contextlib.contextmanager
def exclusive(out: Path) -> Iterator[None]:
    """Hold ``out/.batch.lock`` for the whole run; a second batch on the same folder is refused. The lock
    file is removed when the run ends (also after Ctrl-C), so none stays behind to puzzle anyone."""
    out.mkdir(parents=True, exist_ok=True)
    path = out / LOCK
    with output_folder(out):
        yield from _holding(out, path)


def _holding(out: Path, path: Path) -> Iterator[None]:
    while True:
        lock = _open_lock(path)
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            lock.close()
            if exc.errno in (errno.EAGAIN, errno.EWOULDBLOCK, errno.EACCES):
                raise OutputBusy(f"another batch is already writing to {out}") from None
            # a file system without locks (some network mounts): carry on unlocked rather than refuse
            lock = _open_lock(path)
            break
        if _same_file(lock, path):
            break
        lock.close()            # the holder before us removed the file after we opened it: lock anew
    try:
        _sweep_temporaries(out)
        yield
    finally:
        with contextlib.suppress(OSError):
            path.unlink()       # while still holding it, so a waiting batch re-checks (see above)
        lock.close()


def _sweep_temporaries(out: Path) -> None:
    """Remove the temporary files a batch killed mid-write left (``.<name>.<random>.tmp``) in ``out`` and
    in each ``gradescope/<stem>/``, descriptor-relative: a folder there that is a link is not entered (a
    later write into it refuses it by name), a temporary name that is a link is removed as the link."""
    folders = [out]
    gradescope = out / "gradescope"
    folders += [gradescope / name for name, is_folder in _entries_or_none(gradescope) if is_folder]
    for folder in folders:
        for name, is_folder in _entries_or_none(folder):
            if not is_folder and name.startswith(".") and name.endswith(".tmp"):
                remove(folder / name)


def _entries_or_none(folder: Path) -> list[tuple[str, bool]]:
    try:
        return entries(folder)
    except safe_write.LinkRefused:
        return []


def _open_lock(path: Path) -> TextIO:
    """The lock file, opened to append nothing: created if missing, never through a link planted there."""
    try:
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_APPEND | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise safe_write.LinkRefused(path) from None
        raise
    return os.fdopen(fd, "a")


def _same_file(stream: object, path: Path) -> bool:
    try:
        mine, now = os.fstat(stream.fileno()), os.stat(path)  # type: ignore[attr-defined]
    except OSError:
        return False
    return (mine.st_dev, mine.st_ino) == (now.st_dev, now.st_ino)


def folder_seed(out: Path, given: int | None) -> int:
    """The seed of the grading in ``out``: ``given`` (``--seed N``), else the one stored there by an
    earlier run, else a new secret random one. It is stored in ``out/.seed`` (readable by its owner
    only) so resumes and regrades reuse it; the public default seed is never used for a batch, so the
    hidden goals and worlds cannot be reproduced at home."""
    path = out / SEED
    if given is None:
        try:
            stored = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            stored = None
        seed = stored.get("seed") if isinstance(stored, dict) else None
        if type(seed) is int and 0 <= seed < 2**31:
            return seed
    seed = given if given is not None else secrets.randbelow(2**31)
    write_json(path, {"seed": seed, "set_by": "--seed" if given is not None else "random (secret)"}, 0o600)
    return seed
