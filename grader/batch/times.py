"""``--times FILE.csv``: submission times where the platform's download has none.

Canvas's download says only ``LATE``; Moodle's says nothing. The instructor gives a CSV with an id column
(as the roster reads it: ``id``, ``sid``, ``identifier``, ``email``...) and a time column (``submitted_at``,
``submitted``, ``submission time``, or Moodle's grading worksheet's ``Last modified (submission)``, its
dates such as ``Monday, 2 October 2023, 11:05 PM`` in the downloader's time zone: give ``--timezone``).
A time without an offset needs ``--timezone``; ``-`` or an empty cell means no submission time.
"""

from __future__ import annotations

from datetime import datetime, tzinfo
from pathlib import Path

from grader.batch.late import PolicyError, parse_time
from grader.batch.roster import RosterError, column, plain_id, read_table

TIME_HEADERS = (
    "submitted_at",
    "submitted at",
    "submitted",
    "submission time",
    "last modified (submission)",
    "time",
)
MOODLE_FORMATS = ("%A, %d %B %Y, %I:%M %p", "%A, %d %B %Y, %H:%M", "%d %B %Y, %I:%M %p", "%d %B %Y, %H:%M")


def read_times(path: Path, zone: tzinfo | None) -> dict[str, str]:
    """``{id or e-mail: ISO 8601 time}`` from the file (RosterError for a file it cannot use)."""
    header, rows = read_table(path, "--times")
    id_col = column(header, "id")
    login_col = column(header, "login")
    time_col = next((h for name in TIME_HEADERS for h in header if h == name), None)
    if (id_col is None and login_col is None) or time_col is None:
        raise RosterError(
            f"--times {path}: needs an id (or e-mail) column and a time column "
            f"({', '.join(TIME_HEADERS)}); the headers are {', '.join(header)[:300]}"
        )
    times: dict[str, str] = {}
    for line, row in rows:
        text = row.get(time_col, "").strip()
        if text in ("", "-"):
            continue
        when = _when(text, zone, f"--times {path.name} line {line}")
        for key in (
            plain_id(row.get(id_col, "")) if id_col else "",
            row.get(login_col, "") if login_col else "",
        ):
            if key:
                times[key.casefold() if "@" in key else key] = when.isoformat()
    return times


def _when(text: str, zone: tzinfo | None, where: str) -> datetime:
    for form in MOODLE_FORMATS:
        try:
            local = datetime.strptime(text, form)
        except ValueError:
            continue
        if zone is None:
            raise RosterError(f"{where}: {text!r} is a local date; give --timezone (Europe/London) for it")
        return local.replace(tzinfo=zone)
    try:
        return parse_time(text, zone, where)
    except PolicyError as exc:
        raise RosterError(str(exc)) from None


def time_for(times: dict[str, str], ident_id: str, login: str, sis_id: str) -> str:
    """The time the file gives a student, by id, e-mail or SIS id; "" when it names them not."""
    for key in (ident_id, login.casefold(), sis_id):
        if key and key in times:
            return times[key]
    return ""
