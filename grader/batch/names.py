"""Names a student controls: their id (the class-folder entry) and the paths inside their submission.

Both are hostile input. A name that cannot exist on every file system the grader may write to, or that
could pass for another (a 255-byte id, bytes that are not UTF-8, a file and a folder of the same name, a
path a thousand folders deep, control or invisible characters), must end as that student's ``invalid``
with a reason, never as an exception that stops the class. :func:`check_student_id` and
:func:`check_paths` say why a name is refused; :func:`student_stem` derives the output file name of a
student, unique by construction.
"""

from __future__ import annotations

import hashlib
import re
import unicodedata

from grader.batch.windows_names import same_file_key


class SubmissionRefused(Exception):
    """A submission that will not be graded, with the reason shown to the instructor and the student."""

MAX_ID_BYTES = 128          # student ids are short; the output stem must fit NAME_MAX with suffixes
MAX_PART_BYTES = 128        # one file or folder name inside a submission
MAX_PATH_BYTES = 512        # a whole relative path inside a submission
MAX_DEPTH = 16              # folders inside a submission (a course folder zipped whole is ~4 deep)

# The batch's own files, and names Windows file systems reserve: a stem never equals one of these.
RESERVED = frozenset({"batch", "summary", "gradebook", "gradescope", "con", "prn", "aux", "nul",
                      *(f"com{i}" for i in range(10)), *(f"lpt{i}" for i in range(10))})
_PLAIN = re.compile(r"[a-z0-9](?:[a-z0-9._-]{0,62}[a-z0-9_-])?")   # ids used as they are
_SLUG_DROP = re.compile(r"[^a-z0-9_-]+")
# Characters that print nothing of their own but act on a terminal or the text around them (controls, bidi
# overrides, zero-width characters, line separators: the categories grader.untrusted shows as escapes). A
# name holding one could pass for another student's, or rewrite the instructor's screen.
_HIDDEN = frozenset({"Cc", "Cf", "Zl", "Zp"})


def _hidden_char(text: str) -> str | None:
    return next((ch for ch in text if not (" " <= ch <= "~") and unicodedata.category(ch) in _HIDDEN), None)


def shown(text: str) -> str:
    """``text`` safe to print or store as UTF-8: undecodable bytes (surrogate escapes from a non-UTF-8
    file name) and lone surrogates become U+FFFD."""
    return "".join("\ufffd" if "\ud800" <= ch <= "\udfff" else ch for ch in text) if _has_surrogate(text) \
        else text


def _has_surrogate(text: str) -> bool:
    return any("\ud800" <= ch <= "\udfff" for ch in text)


def _utf8_size(name: str, what: str) -> int:
    try:
        return len(name.encode("utf-8"))
    except UnicodeEncodeError:
        raise SubmissionRefused(f"{what} {shown(name)!r} is not valid UTF-8; rename it") from None


def undecodable(parts: tuple[str, ...]) -> bool:
    """True for a path whose bytes on disk are not UTF-8 (``os.walk`` hands them over as surrogate
    escapes): ``unzip`` writes such names for a zip made on Windows (``notes_caf\\xe9.txt`` in Latin-1)."""
    return any(_has_surrogate(part) for part in parts)


def check_student_id(sid: str) -> None:
    """Refuse an id that is not UTF-8, too long, or holds control or invisible characters
    (SubmissionRefused)."""
    size = _utf8_size(sid, "the folder or zip name")
    if size > MAX_ID_BYTES:
        raise SubmissionRefused(f"the folder or zip name is {size} bytes long; a student id may have at "
                                f"most {MAX_ID_BYTES} (rename it to the student's id)")
    if _hidden_char(sid) is not None:
        raise SubmissionRefused(f"the folder or zip name {ascii(sid)} holds control or invisible characters; "
                                f"rename it to the student's id")


def check_paths(paths: list[tuple[str, ...]] | list[str]) -> None:
    """Refuse a set of submission paths that could not all be written as files on disk: a name too long
    or not UTF-8, a path too deep or too long, control characters, or a name that is both a file and a
    folder (``a`` and ``a/b``), also when they differ only by case."""
    files: dict[str, str] = {}
    folders: dict[str, str] = {}
    for entry in paths:
        parts = tuple(entry.split("/")) if isinstance(entry, str) else entry
        rel = "/".join(parts)
        check_path(parts)
        key = same_file_key(rel)  # Windows: case folded, trailing dots and spaces dropped
        if key in files or key in folders:
            raise SubmissionRefused(f"{shown(rel)!r} and {shown(files.get(key) or folders[key])!r} cannot "
                                    f"both exist on disk (same name, or names that differ only by case or "
                                    f"by a trailing dot or space)")
        files[key] = rel
        for depth in range(1, len(parts)):
            folder = "/".join(parts[:depth])
            fkey = same_file_key(folder)
            if fkey in files:
                raise SubmissionRefused(f"{shown(files[fkey])!r} is a file and also a folder holding "
                                        f"{shown(rel)!r}; both cannot exist on disk")
            folders.setdefault(fkey, folder)


def check_path(parts: tuple[str, ...]) -> None:
    """Refuse one path (its components) that cannot exist on disk everywhere the grader writes."""
    rel = "/".join(parts)
    if len(parts) > MAX_DEPTH:
        raise SubmissionRefused(f"{shown(rel)[:200]!r}... is nested {len(parts)} folders deep; at most "
                                f"{MAX_DEPTH} are accepted")
    if _utf8_size(rel, "the file name") > MAX_PATH_BYTES:
        raise SubmissionRefused(f"{shown(rel)[:200]!r}... is a path longer than {MAX_PATH_BYTES} bytes")
    for part in parts:
        if len(part.encode("utf-8")) > MAX_PART_BYTES:
            raise SubmissionRefused(f"the name {part[:60]!r}... is longer than {MAX_PART_BYTES} bytes")
        if _hidden_char(part) is not None:
            raise SubmissionRefused(f"the name {ascii(part)} holds control or invisible characters")


def student_stem(student_id: str) -> str:
    """The file name (without suffix) of a student's JSON and HTML in the output folder.

    Unique per student by construction, also on case-insensitive file systems, and at most 76 bytes: a
    lower-case id of letters, digits, ``.``, ``_`` and ``-`` (not a reserved name, no dot at either end) is
    used as it is; any other id
    becomes a readable slug, ``~`` and a hash of the exact id (``Alice`` -> ``alice~5c1a...``). A plain
    stem never holds ``~``, so the two kinds cannot meet.
    """
    if _PLAIN.fullmatch(student_id) and student_id.split(".")[0] not in RESERVED:   # con.x is reserved too
        return student_id
    exact = student_id.encode("utf-8", "surrogateescape") if not _has_lone(student_id) \
        else student_id.encode("utf-8", "surrogatepass")
    slug = _SLUG_DROP.sub("-", shown(student_id).lower()).strip("-")[:48] or "student"
    return f"{slug}~{hashlib.sha256(exact).hexdigest()[:16]}"


def _has_lone(text: str) -> bool:
    """True for surrogates that surrogateescape cannot encode (not U+DC80..U+DCFF)."""
    return any("\ud800" <= ch <= "\udfff" and not "\udc80" <= ch <= "\udcff" for ch in text)
