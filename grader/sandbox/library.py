"""The worker's library with its bytecode, built once per content and shared by every bubblewrap worker.

A worker runs `python -I -S -B`: it never writes bytecode, so a library of bare sources (as
`exposed.build_library` copies them for each session) is compiled again by every worker, about a fifth
of its start. This module builds the library once, with a checked-hash `.pyc` beside each source
(Python re-reads the source and checks its hash before it uses one), in a folder named by a hash of
every exposed file's bytes, the interpreter's bytecode tag and magic number: a changed source, a
changed EXPOSED list or another Python gets another folder, never a stale one. The folder is written
under a temporary name and renamed into place, so a concurrent grading process sees it whole or not at
all, and is checked on every use (the same files, the same sources, nothing added); a damaged one is
rebuilt.

Where: $SIMIAM_CACHE_DIR, else $XDG_CACHE_HOME/simiam, else ~/.cache/simiam, in `worker-library/`;
if that cannot be written, a private temporary folder removed when the grading process exits. Only
bubblewrap workers get it (grader.sandbox.isolation.worker_library): bubblewrap binds it read-only at
/library, so no student can change what the next one imports. A plain subprocess runs as a user who
might write to it, so it keeps a fresh copy per session. Who can write the cache folder is the grader's
own user, who can equally edit the grader.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from grader.sandbox import exposed

STALE_SECONDS = 7 * 24 * 3600  # libraries of other versions older than this are removed after a build
_fallback_root: str | None = None
_checked: dict[tuple, str] = {}  # the exposed files' identities -> the library this process checked for them


def cache_root() -> Path:
    """The folder holding the built libraries (it may not exist yet)."""
    base = os.environ.get("SIMIAM_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"), "simiam")
    return Path(base) / "worker-library"


def library_key(sources: dict[str, bytes]) -> str:
    """The folder name for a library of these sources (relative path -> bytes) under this interpreter."""
    digest = hashlib.sha256(f"{sys.implementation.cache_tag}\0".encode() + importlib.util.MAGIC_NUMBER)
    for relative, data in sorted(sources.items()):
        digest.update(relative.encode() + b"\0" + len(data).to_bytes(8, "big") + data)
    return digest.hexdigest()[:32]


def shared_library() -> Path:
    """The library for the exposed files as they are now, with bytecode: reused if intact, else built.

    A grading process checks a library once; later workers reuse it while no exposed file changed
    (same path, modification and change times, size and inode)."""
    paths = {relative: exposed.source_of(relative) for relative in exposed.EXPOSED}
    signature = tuple((relative, str(path), *_identity(path)) for relative, path in paths.items())
    known = _checked.get(signature)
    if known is not None and os.path.isdir(known):
        return Path(known)
    sources = {relative: path.read_bytes() for relative, path in paths.items()}
    key = library_key(sources)
    try:
        folder = _ensure(str(cache_root()), key, sources)
    except OSError:  # no writable cache (read-only home, no HOME): one per grading process instead
        folder = _ensure(_private_root(), key, sources)
    _checked[signature] = folder
    return Path(folder)


def _identity(path: Path) -> tuple[int, int, int, int]:
    """What changes when the file does (ctime too: an edit that restores the mtime still changes it)."""
    info = os.stat(path)
    return info.st_mtime_ns, info.st_ctime_ns, info.st_size, info.st_ino


def _ensure(root: str, key: str, sources: dict[str, bytes]) -> str:
    final = os.path.join(root, key)
    if _intact(final, sources):
        _touch(final)
        return final
    os.makedirs(root, mode=0o700, exist_ok=True)
    building = tempfile.mkdtemp(prefix=f".{key}-", dir=root)
    try:
        exposed.write_library(Path(building), sources, bytecode=True)
        try:
            os.rename(building, final)
        except OSError:  # another process finished first, or a damaged library is in the way
            if _intact(final, sources):
                shutil.rmtree(building, ignore_errors=True)
                return final
            damaged = os.path.join(root, f".damaged-{key}-{os.getpid()}")
            os.rename(final, damaged)
            os.rename(building, final)
            shutil.rmtree(damaged, ignore_errors=True)
    except BaseException:
        shutil.rmtree(building, ignore_errors=True)
        raise
    _prune(root, keep=key)
    return final


def _intact(folder: str, sources: dict[str, bytes]) -> bool:
    """True if `folder` holds exactly these sources and a bytecode file for each, nothing else."""
    paths = {relative: os.path.join(folder, relative) for relative in sources}
    expected = {*paths.values(), *map(exposed.bytecode_of, paths.values())}
    try:
        found = {os.path.join(d, f) for d, _dirs, files in os.walk(folder) for f in files}
        if found != expected:
            return False
        for relative, data in sources.items():
            with open(paths[relative], "rb") as file:
                if file.read() != data:
                    return False
    except OSError:
        return False
    return True


def _prune(root: str, keep: str) -> None:
    """Remove other versions' libraries (and abandoned half-built ones) not used for a week."""
    cutoff = time.time() - STALE_SECONDS
    for entry in os.scandir(root):
        try:
            if entry.name != keep and entry.is_dir(follow_symlinks=False) and entry.stat().st_mtime < cutoff:
                shutil.rmtree(entry.path, ignore_errors=True)
        except OSError:
            continue


def _touch(folder: str) -> None:
    """Mark a library as used now, so that no other process prunes it while it serves (see _prune)."""
    try:
        os.utime(folder)
    except OSError:
        pass


def _private_root() -> str:
    global _fallback_root
    if _fallback_root is None:
        import atexit

        _fallback_root = tempfile.mkdtemp(prefix="simiam-library-")
        atexit.register(shutil.rmtree, _fallback_root, ignore_errors=True)
    return _fallback_root
