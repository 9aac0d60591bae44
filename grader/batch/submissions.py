"""The class folder: one sub-folder or ``.zip`` per student, named by student id.

:func:`discover` lists the students; :func:`read_submission` reads one of them into memory as
``{relative path: bytes}`` (the same limits for folders and zips), finds the folder that holds the
student's files (a zip of ``week3/`` or of the whole course folder is fine) and hashes the content.
What is hashed is exactly what is graded: the grading process receives these bytes, never the path.
"""

from __future__ import annotations

import base64
import hashlib
import os
from dataclasses import dataclass, field
from pathlib import Path

from grader.batch.export_files import Export, read_members
from grader.batch.identity import Identity
from grader.batch.names import MAX_DEPTH, check_path, check_paths, check_student_id, shown, undecodable
from grader.batch.windows_names import leave_out
from grader.batch.zips import JUNK_PARTS, Limits, SubmissionRefused, is_junk, read_zip
from simiam.course.weeks import all_weeks

# The files students edit in any week (each week declares its own, simiam/course/weeks/weekN.py); used
# only to find the submission's root folder inside a zip.
STUDENT_FILES = frozenset(name for week in all_weeks() for name in week.student_files)


@dataclass(frozen=True)
class Student:
    """One entry of the class folder."""

    id: str            # the folder name, or the zip name without ``.zip``; a platform's own id
    path: Path
    kind: str          # "folder" | "zip" | "clash" (both a folder and a zip with this id) | "link"
    #                    | "export" (files in a platform's download) | "held" (the instructor's to sort out)
    identity: Identity | None = None
    members: tuple[tuple[str, str], ...] = ()   # "export": (name in the export, path in the submission)
    held: str = ""                              # "held": why, for the instructor
    notices: tuple[str, ...] = ()               # what the student reads about their export entries
    export: Export | None = field(default=None, compare=False, repr=False)


@dataclass
class Submission:
    """A student's files, read and checked. ``refused`` is set instead of ``files`` when not gradable."""

    student: Student
    files: dict[str, bytes] = field(default_factory=dict)
    sha256: str = ""
    refused: str | None = None
    root: str = ""     # the folder inside the zip/folder the files were taken from ("" = top level)
    notices: list[str] = field(default_factory=list)   # what the student is told besides the checks
    held: str | None = None   # set instead of ``files``: an instructor-side problem (status "held")


def discover(batch_dir: Path) -> list[Student]:
    """Every student in ``batch_dir``, sorted by id. Hidden entries and stray files are skipped; a link
    to a folder or zip is listed (kind "link") so that it is reported, never followed nor silently lost."""
    found: dict[str, list[tuple[str, Path]]] = {}
    for entry in sorted(batch_dir.iterdir()):
        if entry.name.startswith(".") or entry.name.startswith("__MACOSX"):
            continue
        if entry.is_symlink() and (entry.is_dir() or entry.suffix.lower() in (".zip", "")):
            found.setdefault(entry.name[:-4] if entry.suffix.lower() == ".zip" else entry.name,
                             []).append(("link", entry))
        elif entry.is_dir() and not entry.is_symlink():
            found.setdefault(entry.name, []).append(("folder", entry))
        elif entry.suffix.lower() == ".zip" and entry.is_file() and not entry.is_symlink():
            found.setdefault(entry.name[:-4], []).append(("zip", entry))
    students = []
    for sid, entries in sorted(found.items()):
        kind, path = entries[0] if len(entries) == 1 else ("clash", entries[0][1])
        students.append(Student(sid, path, kind))
    return students


def read_submission(student: Student, limits: Limits | None = None, week: int | None = None) -> Submission:
    """Read and check one student's files; a refusal is recorded, never raised. ``week`` (the batch's)
    picks ``weekN/`` in a submission holding several weeks' folders."""
    limits = limits or Limits()
    if student.kind == "clash":       # made on the instructor's side: never the student's fault
        return Submission(student, sha256=_hash_text(f"clash {student.id}"),
                          held=f"both a folder and a zip are named {shown(student.id)!r}; keep the one "
                               f"that is the submission and rerun")
    if student.kind == "held":
        return Submission(student, sha256=_hash_text(f"held {student.held} {student.members}"),
                          held=shown(student.held))
    if student.kind == "export":
        return _read_export_student(student, limits, week)
    try:
        check_student_id(student.id)
        if student.kind == "link":
            raise SubmissionRefused(f"{student.path.name} is a link; links are not followed "
                                    "(copy the submission into the class folder)")
        skipped: list[str] = []
        raw = read_zip(student.path, limits) if student.kind == "zip" \
            else read_folder(student.path, limits, skipped)
        left_out: list[str] = []  # names Windows cannot store (windows_names), each said in a note
        raw = leave_out(raw, left_out)
        check_paths(list(raw))
        root, files = find_root(raw, week)
        if not files:
            raise SubmissionRefused("the submission has no files")
    except SubmissionRefused as refused:
        return Submission(student, sha256=_hash_path(student.path), refused=shown(str(refused)))
    except OSError as exc:          # unreadable file, vanished folder...: this student only
        return Submission(student, sha256=_hash_path(student.path),
                          refused=shown(f"the submission could not be read ({exc.strerror or exc})"))
    except Exception as exc:  # noqa: BLE001 - whatever one submission does to the reader is its problem
        return Submission(student, sha256=_hash_path(student.path),
                          refused=shown(f"the submission could not be read ({type(exc).__name__}: "
                                        f"{str(exc)[:300]})"))
    return Submission(student, files=files, sha256=content_hash(files, skipped + left_out), root=root,
                      notices=[skipped_note(name) for name in skipped] + left_out)


def _read_export_student(student: Student, limits: Limits, week: int | None) -> Submission:
    """A student whose files are entries of a platform's download; a zip they uploaded is read as their
    own zip would be (same limits, in memory) and its files placed beside their other files."""
    assert student.export is not None, "an export student carries its export"
    listing = "\n".join(f"{name}\x00{rel}" for name, rel in student.members)
    try:
        check_student_id(student.id)
        raw = read_members(student.export, list(student.members), limits)
        for rel in [r for r in raw if r.lower().endswith(".zip")]:
            inner = read_zip(raw.pop(rel), limits, label=rel)
            for path, data in inner.items():
                if path in raw:
                    raise SubmissionRefused(f"{rel} holds {path}, and the submission has another {path}")
                raw[path] = data
        if sum(map(len, raw.values())) > limits.max_total_bytes or len(raw) > limits.max_files:
            raise SubmissionRefused(f"the submission is over the limits ({limits.max_files} files, "
                                    f"{limits.max_total_bytes} bytes)")
        left_out: list[str] = []
        raw = leave_out(raw, left_out)
        check_paths(list(raw))
        root, files = find_root(raw, week)
        if not files:
            raise SubmissionRefused("the submission has no files")
    except SubmissionRefused as refused:
        return Submission(student, sha256=_hash_text(f"refused {listing} {refused}"),
                          refused=shown(str(refused)),
                          notices=list(student.notices))
    except Exception as exc:  # noqa: BLE001 - whatever one submission does to the reader is its problem
        return Submission(student, sha256=_hash_text(f"refused {listing} {type(exc).__name__}"),
                          refused=shown(f"the submission could not be read ({type(exc).__name__}: "
                                        f"{str(exc)[:300]})"))
    return Submission(student, files=files, sha256=content_hash(files, list(student.notices) + left_out),
                      root=root, notices=list(student.notices) + left_out)


def _hash_text(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()


def skipped_note(name: str) -> str:
    """What the student reads about a file left out because its name is not UTF-8."""
    return (f"{name}: its name is not valid UTF-8 (a zip made on Windows and unpacked elsewhere?); the "
            f"grader does not use this file, so it was skipped")


def read_folder(folder: Path, limits: Limits | None = None,
                skipped: list[str] | None = None) -> dict[str, bytes]:
    """Read a student's folder with the zip limits. A link that leads outside the folder is refused.

    A file whose name is not UTF-8 is left out, named (as shown) in ``skipped``, when the grader would
    not use it anyway (its name is none of the course's files): a student's ``notes_caf\\xe9.txt`` must not
    cost their grade. Such a name on a course file is still refused (check_path), and so is any name when
    ``skipped`` is None."""
    limits = limits or Limits()
    base = folder.resolve()
    files: dict[str, bytes] = {}
    total = 0
    for dirpath, dirnames, filenames in os.walk(folder, followlinks=False, onerror=_walk_error):
        here = Path(dirpath)
        for name in sorted(dirnames):
            link = here / name
            if name in JUNK_PARTS:
                dirnames.remove(name)
            elif link.is_symlink():
                _check_inside(link, base, folder)
                dirnames.remove(name)      # never walk through a link, even an inward one
        parts = here.relative_to(folder).parts
        if len(parts) >= MAX_DEPTH and dirnames:   # refused before walking on: 1000 deep costs 16 steps
            raise SubmissionRefused(f"{shown('/'.join(parts))[:200]}/{shown(dirnames[0])[:60]}/... is nested "
                                    f"more than {MAX_DEPTH} folders deep; at most {MAX_DEPTH} are accepted")
        for name in sorted(filenames):
            path = here / name
            rel_parts = path.relative_to(folder).parts
            if is_junk(rel_parts):
                continue
            if skipped is not None and undecodable(rel_parts) and name not in STUDENT_FILES:
                skipped.append(shown("/".join(rel_parts)))
                continue
            check_path(rel_parts)
            if path.is_symlink():
                _check_inside(path, base, folder)
            if not path.is_file():
                raise SubmissionRefused(f"{'/'.join(rel_parts)} is not a regular file")
            size = path.stat().st_size
            if len(files) >= limits.max_files:
                raise SubmissionRefused(f"the folder has more than {limits.max_files} files")
            if size > limits.max_file_bytes or total + size > limits.max_total_bytes:
                raise SubmissionRefused(f"{'/'.join(rel_parts)} is {size} bytes; the limits are "
                                        f"{limits.max_file_bytes} per file and "
                                        f"{limits.max_total_bytes} in all")
            data = path.read_bytes()
            total += len(data)
            files["/".join(rel_parts)] = data
    return files


def _walk_error(exc: OSError) -> None:
    raise exc           # an unreadable sub-folder is this submission's problem, not silently skipped


def _check_inside(link: Path, base: Path, folder: Path) -> None:
    try:
        target = link.resolve()
    except (OSError, RuntimeError):        # a link loop: Python 3.11 raises RuntimeError
        raise SubmissionRefused(f"{link.relative_to(folder)} is a link that leads nowhere (a loop?); "
                                f"links are not followed") from None
    if target != base and base not in target.parents:
        raise SubmissionRefused(f"{link.relative_to(folder)} is a link to something outside the submission; "
                                f"links are not followed")


def find_root(files: dict[str, bytes], week: int | None = None) -> tuple[str, dict[str, bytes]]:
    """The folder holding the student's files, and the files re-rooted there.

    A single top-level folder (``alice.zip`` containing ``week3/...``) is stepped into; failing that, the
    shallowest folder with the most course files (``simiam/assignments/week3/``) is chosen, among the
    folders named ``week<week>`` when there are any (a whole ``assignments/`` folder holds every week, and
    week 4's folder has the most files).
    """
    root = ""
    while files and not any("/" not in p for p in files):
        tops = {p.split("/", 1)[0] for p in files}
        if len(tops) != 1:
            break
        top = tops.pop()
        root = f"{root}{top}/"
        files = {p.split("/", 1)[1]: data for p, data in files.items()}
    if any(p in STUDENT_FILES for p in files):
        return root.rstrip("/"), files
    score: dict[str, int] = {}
    for p in files:
        folder, _, name = p.rpartition("/")
        if name in STUDENT_FILES:
            score[folder] = score.get(folder, 0) + 1
    if not score:
        return root.rstrip("/"), files
    named = [f for f in score if week is not None and f.rsplit("/", 1)[-1].lower() == f"week{week}"]
    best = max(named or score, key=lambda f: (score[f], -f.count("/"), f))
    prefix = best + "/"
    return f"{root}{best}", {p[len(prefix):]: d for p, d in files.items() if p.startswith(prefix)}


def content_hash(files: dict[str, bytes], skipped: list[str] | None = None) -> str:
    """SHA-256 of the files' names and bytes, independent of order, timestamps and zip packaging, and of
    the names of the files skipped (their notices are part of the result, so a rename regrades)."""
    digest = hashlib.sha256()
    for rel in sorted(files):
        digest.update(rel.encode() + b"\x00" + hashlib.sha256(files[rel]).digest())
    for name in sorted(skipped or []):
        digest.update(b"\x01skipped\x00" + name.encode())
    return digest.hexdigest()


def _hash_path(path: Path, max_entries: int = 2000) -> str:
    """Hash of what is on disk for a refused submission (so fixing the zip triggers a regrade). Bounded:
    a folder a thousand deep or with a million files costs at most ``max_entries`` steps; never raises."""
    digest = hashlib.sha256(os.fsencode(path.name))
    try:
        if path.is_symlink():       # never read through a link
            digest.update(os.fsencode(os.readlink(path)))
        elif path.is_file():
            with path.open("rb") as stream:
                while chunk := stream.read(1 << 20):
                    digest.update(chunk)
        else:
            seen = 0
            for dirpath, dirnames, filenames in os.walk(path, followlinks=False):
                dirnames.sort()
                for name in sorted(filenames):
                    full = os.path.join(dirpath, name)
                    digest.update(os.fsencode(os.path.relpath(full, path)))
                    digest.update(str(os.lstat(full).st_size).encode())
                seen += 1 + len(filenames)
                if seen > max_entries:
                    break
    except (OSError, RecursionError, ValueError):
        pass
    return digest.hexdigest()


def pack(files: dict[str, bytes]) -> dict[str, str]:
    """Files as JSON-safe base64 text, to send to a grading process (local or on another machine)."""
    return {rel: base64.b64encode(data).decode("ascii") for rel, data in files.items()}


def unpack(packed: dict[str, str], into: Path) -> Path:
    """Write packed files under ``into`` (names were checked when read) and return ``into``."""
    for rel, text in packed.items():
        target = into.joinpath(*rel.split("/"))
        if into.resolve() not in target.resolve().parents:   # defence in depth; read_* already refused
            raise SubmissionRefused(f"{rel} would land outside the submission folder")
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(base64.b64decode(text))
    return into
