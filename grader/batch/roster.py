"""``--roster FILE.csv``: who is in the class, to name who did not submit and to fill in names.

Headers are matched loosely (case, spaces and order do not matter):

| field | headers read |
|---|---|
| id | ``id``, ``student id``, ``user id``, ``canvas user id``, ``sid``, ``participant id``, ``identifier`` |
| name | ``name``, ``student``, ``full name``, ``student name`` (or ``first name`` + ``last name``) |
| login | ``login``, ``email``, ``email address``, ``e-mail``, ``sis login id``, ``username`` |
| section | ``section``, ``sections`` |
| sis_id | ``sis user id``, ``sis id``, ``id number``, ``student number`` |
| extension | ``extension``, ``extension until``, ``extra days`` (a new deadline, or ``2d``/``36h``/days) |

So a Canvas gradebook export (Student, ID, SIS User ID, SIS Login ID, Section; its "Points Possible" row
and Canvas's "Student, Test" are skipped), Moodle's grading worksheet (Identifier ``Participant 123``, Full
name, Email address) and Gradescope's roster (First Name, Last Name, SID, Email) are rosters as they come.
A roster is the instructor's file, still read with caps (size, rows, cell length) and clear errors.
"""

from __future__ import annotations

import csv
import dataclasses
import io
from dataclasses import dataclass
from pathlib import Path

from grader.batch.identity import Identity

MAX_BYTES = 32 * 1024 * 1024
MAX_ROWS = 100_000
HEADERS = {
    "id": (
        "id",
        "student id",
        "user id",
        "canvas user id",
        "canvas id",
        "sid",
        "participant id",
        "identifier",
    ),
    "name": ("name", "student", "full name", "student name"),
    "first": ("first name",),
    "last": ("last name", "surname"),
    "login": ("login", "email", "email address", "e-mail", "sis login id", "login id", "username"),
    "section": ("section", "sections"),
    "sis_id": ("sis user id", "sis id", "id number", "student number"),
    "extension": ("extension", "extension until", "extended deadline", "extra days"),
}


class RosterError(ValueError):
    """A roster or times file that cannot be read (exit status 2 with this message)."""


@dataclass(frozen=True)
class RosterRow:
    """One student of the roster; ``extension`` is the raw cell (read against the deadline later)."""

    identity: Identity
    extension: str = ""
    line: int = 0


def read_table(path: Path, what: str) -> tuple[list[str], list[tuple[int, dict[str, str]]]]:
    """A CSV's normalised headers and its rows (line number, header -> cell), UTF-8 (BOM or not), ``,``
    or ``;`` (RosterError)."""
    try:
        size = path.stat().st_size
        if size > MAX_BYTES:
            raise RosterError(f"{what} {path} is {size} bytes; at most {MAX_BYTES}")
        text = path.read_bytes().decode("utf-8-sig")
    except OSError as exc:
        raise RosterError(f"{what} {path} cannot be read ({exc.strerror or exc})") from None
    except UnicodeDecodeError:
        raise RosterError(f"{what} {path} is not UTF-8 text; save it as CSV UTF-8") from None
    first = text.split("\n", 1)[0]
    delimiter = ";" if first.count(";") > first.count(",") else ","
    try:
        reader = csv.reader(io.StringIO(text), delimiter=delimiter)
        header = [" ".join(h.strip().lower().split()) for h in next(reader, [])]
        rows: list[tuple[int, dict[str, str]]] = []
        for number, cells in enumerate(reader, start=2):
            if len(rows) >= MAX_ROWS:
                raise RosterError(f"{what} {path} has more than {MAX_ROWS} rows")
            if any(c.strip() for c in cells):
                rows.append((number, {h: c.strip()[:500] for h, c in zip(header, cells, strict=False)}))
    except csv.Error as exc:
        raise RosterError(f"{what} {path}: {exc}") from None
    return header, rows


def column(header: list[str], field: str) -> str | None:
    """The header that holds ``field`` (HEADERS), None if the file has none."""
    return next((h for name in HEADERS[field] for h in header if h == name), None)


def plain_id(text: str) -> str:
    """``Participant 123456`` (Moodle's Identifier) -> ``123456``; other ids unchanged."""
    text = text.strip()
    return text.split(" ", 1)[1].strip() if text.lower().startswith("participant ") else text


def read_roster(path: Path, platform: str = "folder") -> list[RosterRow]:
    """The roster's students (RosterError for a file without an id or login column, or a repeated id)."""
    header, rows = read_table(path, "--roster")
    cols = {field: column(header, field) for field in HEADERS}
    if cols["id"] is None and cols["login"] is None:
        raise RosterError(
            f"--roster {path}: no id column (one of: {', '.join(HEADERS['id'])}) and no "
            f"login or e-mail column; the headers are {', '.join(header)[:300]}"
        )
    roster: list[RosterRow] = []
    seen: dict[str, int] = {}
    for line, row in rows:
        get = {field: row.get(col, "") if col else "" for field, col in cols.items()}
        if "points possible" in get["name"].lower() or get["name"].lower() in (
            "student, test",
            "test student",
        ):
            continue  # Canvas's points row and its test student
        sid = plain_id(get["id"]) or get["login"] or get["sis_id"]
        if not sid:
            continue
        if sid in seen:
            raise RosterError(f"--roster {path}: id {sid!r} is on lines {seen[sid]} and {line}; keep one")
        seen[sid] = line
        name = get["name"] or " ".join(p for p in (get["first"], get["last"]) if p)
        roster.append(
            RosterRow(
                Identity(
                    id=sid,
                    name=name,
                    login=get["login"],
                    section=get["section"],
                    sis_id=get["sis_id"],
                    platform=platform,
                ),
                get["extension"],
                line,
            )
        )
    return roster


@dataclass
class Matched:
    """The roster laid over the submissions."""

    identities: dict[str, Identity]  # submission id -> identity filled from its roster row
    extensions: dict[str, str]  # submission id -> the roster's extension cell
    missing: list[str]  # roster ids with no submission
    not_on_roster: list[str]  # submission ids no roster row names
    notes: list[str]


def match(found: dict[str, Identity], roster: list[RosterRow]) -> Matched:
    """Each submission's roster row: by id, then SIS id, then login/e-mail (case-insensitive)."""
    by_id = {r.identity.id: r for r in roster}
    by_sis = {r.identity.sis_id: r for r in roster if r.identity.sis_id}
    by_login = {r.identity.login.casefold(): r for r in roster if r.identity.login}
    result = Matched({}, {}, [], [], [])
    taken: dict[str, str] = {}
    for sid, ident in sorted(found.items()):
        row = (
            by_id.get(ident.id)
            or by_sis.get(ident.id)
            or (ident.sis_id and by_id.get(ident.sis_id))
            or (ident.sis_id and by_sis.get(ident.sis_id))
            or (ident.login and by_login.get(ident.login.casefold()))
            or None
        )
        if row is None:
            result.identities[sid] = ident
            result.not_on_roster.append(sid)
            continue
        if row.identity.id in taken:
            result.notes.append(
                f"roster line {row.line} ({row.identity.id}) matches two submissions: "
                f"{taken[row.identity.id]} and {sid}"
            )
        taken.setdefault(row.identity.id, sid)
        result.identities[sid] = _filled(ident, row.identity)
        if row.extension:
            result.extensions[sid] = row.extension
    result.missing = [r.identity.id for r in roster if r.identity.id not in taken]
    return result


def _filled(ident: Identity, row: Identity) -> Identity:
    """The submission's identity with the roster's name (always for Canvas, whose download has only a
    lower-cased sortable name), login, section and SIS id where the submission has none."""
    return dataclasses.replace(
        ident,
        name=row.name if row.name and (ident.platform == "canvas" or not ident.name) else ident.name,
        login=ident.login or row.login,
        section=ident.section or row.section,
        sis_id=ident.sis_id or row.sis_id,
    )

