"""What ``grade weekN --batch SOURCE`` grades: SOURCE recognised by its own layout, grouped per student,
with the roster, the submission times and the late policy laid over it.

SOURCE is, in the order they are tried:

- Gradescope's export: ``submission_metadata.yml`` (grader/batch/gradescope_export.py);
- Moodle's "Download all submissions" (grader/batch/moodle_download.py);
- Canvas's "Download Submissions" (grader/batch/canvas_download.py);
- otherwise the class folder: one folder or ``.zip`` per student id (grader/batch/submissions.py).

A platform's download may be the ``.zip`` as downloaded or the folder it was extracted to (a single
wrapping folder is stepped into). Every student keeps one :class:`Identity`; anything the grader cannot
place or tell apart is named for the instructor (``unplaced``, ``held``), never charged to a student.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from datetime import datetime, timezone, tzinfo
from pathlib import Path
from zoneinfo import ZoneInfo, ZoneInfoNotFoundError

from grader.batch import canvas_download, gradescope_export, moodle_download
from grader.batch.export_files import Export, ExportRefused, list_export
from grader.batch.found import Found
from grader.batch.identity import Identity
from grader.batch.late import (
    LatePolicy,
    PolicyError,
    parse_duration,
    parse_extension,
    parse_penalty,
    parse_percent,
    parse_time,
)
from grader.batch.names import shown
from grader.batch.roster import RosterError, match, read_roster
from grader.batch.submissions import Student, discover
from grader.batch.times import read_times, time_for

LAYOUTS = {
    "folder": "class folder (one folder or .zip per student id)",
    "canvas": 'Canvas "Download Submissions"',
    "moodle": 'Moodle "Download all submissions"',
    "gradescope": 'Gradescope "Export Submissions"',
}
MAX_LISTED = 200  # names listed in batch.json per kind of note


class IntakeError(ValueError):
    """The class cannot be read (exit status 2 with this message)."""


@dataclass(frozen=True)
class IntakeOptions:
    """The intake and late-policy options of ``grade --batch``."""

    roster: Path | None = None
    times: Path | None = None
    timezone: str | None = None
    deadline: str | None = None
    late_penalty: str | None = None
    late_cap: str | None = None
    late_floor: str | None = None
    grace: str | None = None
    file_times: bool = False  # --file-times: the files' own times where nothing else gives one

    @classmethod
    def from_args(cls, given: dict) -> IntakeOptions:
        """From the ``grade`` parser's values (missing ones stay None)."""

        def path(key: str) -> Path | None:
            return Path(given[key]) if given.get(key) else None

        def text(key: str) -> str | None:
            value = given.get(key)
            return str(value) if value else None

        return cls(
            roster=path("roster"),
            times=path("times"),
            timezone=text("timezone"),
            deadline=text("deadline"),
            late_penalty=text("late_penalty"),
            late_cap=text("late_cap"),
            late_floor=text("late_floor"),
            grace=text("grace"),
            file_times=bool(given.get("file_times")),
        )

    def zone(self) -> tzinfo | None:
        """``--timezone`` (an IANA name such as Europe/London), None when not given (IntakeError)."""
        if not self.timezone:
            return None
        try:
            return ZoneInfo(self.timezone)
        except (ZoneInfoNotFoundError, ValueError):
            raise IntakeError(
                f"--timezone {self.timezone!r} is not a time zone name (Europe/London, America/New_York, UTC)"
            ) from None

    def policy(self) -> LatePolicy | None:
        """The late policy; None without ``--deadline`` (IntakeError: a policy option alone, unreadable)."""
        if not self.deadline:
            if any((self.late_penalty, self.late_cap, self.late_floor, self.grace)):
                raise IntakeError("--late-penalty, --late-cap, --late-floor and --grace need --deadline")
            return None
        try:
            percent, interval = parse_penalty(self.late_penalty) if self.late_penalty else (0.0, 86400)
            return LatePolicy(
                deadline=parse_time(self.deadline, self.zone()),
                percent=percent,
                interval_s=interval,
                cap_percent=parse_percent(self.late_cap, "--late-cap") if self.late_cap else None,
                floor_percent=parse_percent(self.late_floor, "--late-floor") if self.late_floor else None,
                grace_s=parse_duration(self.grace) if self.grace else 0,
            )
        except PolicyError as exc:
            raise IntakeError(str(exc)) from None


@dataclass
class ClassList:
    """The students to grade and everything the instructor should hear about the intake."""

    layout: str
    source: Path
    students: list[Student]
    unplaced: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    roster: list[Identity] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)
    not_on_roster: list[str] = field(default_factory=list)
    extensions: dict[str, datetime] = field(default_factory=dict)
    policy: LatePolicy | None = None
    no_time_late: list[str] = field(default_factory=list)  # Canvas said LATE, no time to charge by

    def described(self) -> str:
        """The first line a batch prints: what SOURCE was recognised as."""
        return f"{LAYOUTS[self.layout]}: {self.source.name}, {len(self.students)} students"

    def meta(self) -> dict:
        """For batch.json and the summary (the shared convention's ``roster`` and ``missing``)."""
        return {
            "layout": self.layout,
            "layout_text": LAYOUTS[self.layout],
            "roster": [r.to_json() for r in self.roster],
            "missing": list(self.missing),
            "intake": {
                "unplaced": self.unplaced[:MAX_LISTED],
                "unplaced_count": len(self.unplaced),
                "not_on_roster": self.not_on_roster[:MAX_LISTED],
                "not_on_roster_count": len(self.not_on_roster),
                "notes": self.notes[:MAX_LISTED],
                "late_without_time": self.no_time_late[:MAX_LISTED],
                "late_policy": self.policy.to_json() if self.policy else None,
                "late_policy_text": self.policy.describe() if self.policy else "",
            },
        }

    def messages(self) -> list[str]:
        """What the batch prints for the instructor before grading starts."""
        lines = [f"reading {self.described()}"]
        if self.policy:
            lines.append(f"late policy: {self.policy.describe()}")
        for note in self.notes[:50]:
            lines.append(f"note: {note}")
        lines += [f"not placed (not graded): {shown(n)}" for n in self.unplaced[:50]]
        if self.not_on_roster:
            lines.append(f"not on the roster (graded, check them): {', '.join(self.not_on_roster[:50])}")
        if self.missing:
            lines.append(
                f"on the roster, no submission: {len(self.missing)} ({', '.join(self.missing[:50])})"
            )
        for sid in self.no_time_late[:50]:
            lines.append(f"{sid}: marked late by Canvas, no submission time: give --times")
        return lines


def read_class(source: Path, options: IntakeOptions, out: Path | None = None) -> ClassList:
    """Recognise SOURCE, group it per student and lay the roster, times and late policy over it."""
    policy = options.policy()
    zone = options.zone()
    if not source.exists():
        raise IntakeError(
            f"{source} is not a folder of submissions nor a platform's download (it does not exist)"
        )
    klass = _recognise(source, out)
    if options.times:
        try:
            times = read_times(options.times, zone)
        except RosterError as exc:
            raise IntakeError(str(exc)) from None
        klass.students = [_with_time(s, times) for s in klass.students]
    if options.file_times:
        klass.students = [_with_file_time(s, zone) for s in klass.students]
    if options.roster:
        try:
            rows = read_roster(options.roster, platform=klass.layout)
        except RosterError as exc:
            raise IntakeError(str(exc)) from None
        matched = match({s.id: _identity(s) for s in klass.students}, rows)
        klass.students = [dataclasses.replace(s, identity=matched.identities[s.id]) for s in klass.students]
        klass.roster = [r.identity for r in rows]
        klass.missing, klass.not_on_roster = matched.missing, matched.not_on_roster
        klass.notes += matched.notes
        if policy:
            for sid, cell in matched.extensions.items():
                try:
                    until = parse_extension(cell, policy.deadline, zone)
                except PolicyError as exc:
                    raise IntakeError(f"--roster, extension of {sid}: {exc}") from None
                if until is not None:
                    klass.extensions[sid] = until
    klass.policy = policy
    untimed = [s.id for s in klass.students if not _identity(s).submitted_at and not _identity(s).late_flag]
    if policy and untimed:
        klass.notes.append(f"{len(untimed)} submissions have no submission time (the download gives none): "
                           f"not charged; give --times ({', '.join(untimed[:20])}"
                           f"{', ...' if len(untimed) > 20 else ''})")
    klass.no_time_late = [
        s.id for s in klass.students if (i := _identity(s)).late_flag and not i.submitted_at
    ]
    if klass.no_time_late and not policy:
        klass.notes.append(
            f"{len(klass.no_time_late)} submissions are marked late by Canvas; no --deadline "
            f"was given, so no late penalty applies"
        )
        klass.no_time_late = []
    return klass


def _identity(student: Student) -> Identity:
    return student.identity or Identity(id=student.id)


def _with_time(student: Student, times: dict[str, str]) -> Student:
    ident = _identity(student)
    when = time_for(times, ident.id, ident.login, ident.sis_id)
    return (
        dataclasses.replace(student, identity=dataclasses.replace(ident, submitted_at=when))
        if when
        else student
    )


def _with_file_time(student: Student, zone: tzinfo | None) -> Student:
    """The student with the latest of their files' own times as submission time (``--file-times``, asked
    for by the instructor), where neither the platform nor ``--times`` gave one. A zip's times are local
    to whoever made it: they need ``--timezone`` (IntakeError)."""
    ident = _identity(student)
    if ident.submitted_at:
        return student
    when: datetime | None = None
    if student.export is not None:
        names = {name for name, _rel in student.members}
        entries = [e for e in student.export.entries if e.name in names]
        if student.export.is_zip and entries:
            if zone is None:
                raise IntakeError(
                    "--file-times on a zip: its times are local to whoever made it; give --timezone"
                )
            stamps = [datetime(y, mo, d, h, mi, s) for e in entries if len(e.local_time) >= 6
                      for y, mo, d, h, mi, s in [e.local_time[:6]]]
            when = max(stamps).replace(tzinfo=zone) if stamps else None
        elif entries:
            when = datetime.fromtimestamp(max(e.mtime for e in entries), timezone.utc)
    elif student.kind in ("folder", "zip"):
        try:
            when = datetime.fromtimestamp(student.path.lstat().st_mtime, timezone.utc)
        except OSError:
            when = None
    if when is None:
        return student
    return dataclasses.replace(student, identity=dataclasses.replace(ident, submitted_at=when.isoformat()))


def _recognise(source: Path, out: Path | None) -> ClassList:
    """The layout of SOURCE and its students."""
    if source.is_dir():
        inner = _wrapped(source, out)
        top = sorted(e.name for e in inner.iterdir() if not e.name.startswith((".", "__MACOSX")))
        if "submission_metadata.yml" in top or moodle_download.looks_like(top) or _canvas_names(inner, top):
            if out is not None and _holds(inner, out):
                raise IntakeError("--out must not be inside the platform's download; choose another folder")
            try:
                return _from_export(inner, list_export(inner))
            except ExportRefused as exc:
                raise IntakeError(str(exc)) from None
        students = [s for s in discover(source) if out is None or not _holds(s.path, out)]
        return ClassList(
            "folder", source, [dataclasses.replace(s, identity=Identity(id=s.id)) for s in students]
        )
    if source.suffix.lower() != ".zip":
        raise IntakeError(f"{source} is neither a folder of submissions nor a platform's .zip download")
    try:
        export = list_export(source)
    except ExportRefused as exc:
        raise IntakeError(str(exc)) from None
    return _from_export(source, export)


def _canvas_names(folder: Path, top: list[str]) -> bool:
    files = [n for n in top if (folder / n).is_file() and not (folder / n).is_symlink()]
    matched = sum(1 for n in files if canvas_download.ENTRY.match(n))
    return matched > 0 and matched * 2 > len(top)


def _wrapped(folder: Path, out: Path | None) -> Path:
    """The folder a download was extracted to, stepping into one wrapping folder (``CS101 submissions/``)
    when the download is inside it; ``folder`` itself otherwise."""
    entries = [
        e
        for e in folder.iterdir()
        if not e.name.startswith((".", "__MACOSX")) and (out is None or not _holds(e, out))
    ]
    if len(entries) == 1 and entries[0].is_dir() and not entries[0].is_symlink():
        inner = entries[0]
        top = sorted(e.name for e in inner.iterdir() if not e.name.startswith((".", "__MACOSX")))
        if "submission_metadata.yml" in top or moodle_download.looks_like(top) or _canvas_names(inner, top):
            return inner
    return folder


def _holds(path: Path, out: Path) -> bool:
    path, out = path.resolve(), out.resolve()
    return path == out or path in out.parents


def _from_export(source: Path, export: Export) -> ClassList:
    notes: list[str] = []
    try:
        if gradescope_export.metadata_name(export):
            layout = "gradescope"
            found, unplaced, notes = gradescope_export.read_gradescope(export)
        else:
            top = _step_in(export, export.top_names()) if export.is_zip else export.top_names()
            layout = (
                "moodle"
                if moodle_download.looks_like(export.top_names())
                else "canvas"
                if canvas_download.looks_like(export.top_names(), export)
                else ""
            )
            if not layout:
                raise IntakeError(
                    f"{source.name} is not a Canvas, Moodle or Gradescope download (its first "
                    f"entries: {', '.join(shown(n) for n in top[:5])}); a class folder must be "
                    f"a folder with one sub-folder or .zip per student"
                )
            found, unplaced = (
                moodle_download.read_moodle if layout == "moodle" else canvas_download.read_canvas
            )(export)
    except ExportRefused as exc:
        raise IntakeError(str(exc)) from None
    students = [_student(sid, f, source, export) for sid, f in sorted(found.items())]
    return ClassList(layout, source, students, unplaced=sorted(export.problems + unplaced), notes=notes)


def _step_in(export: Export, top: list[str]) -> list[str]:
    """A zip whose entries all sit in one folder (a download zipped again): its entries re-rooted there."""
    if len(top) == 1 and all("/" in e.name for e in export.entries):
        prefix = top[0] + "/"
        inner = sorted({e.name[len(prefix) :].split("/", 1)[0] for e in export.entries})
        if moodle_download.looks_like(inner) or any(canvas_download.ENTRY.match(n) for n in inner):
            export.step_into(top[0])
            return export.top_names()
    return top


def _student(sid: str, found: Found, source: Path, export: Export) -> Student:
    members = tuple(found.members)
    if found.held:
        return Student(
            sid,
            source,
            "held",
            identity=found.identity,
            members=members,
            held=found.held,
            notices=tuple(found.notices),
            export=export,
        )
    return Student(
        sid,
        source,
        "export",
        identity=found.identity,
        members=members,
        notices=tuple(found.notices),
        export=export,
    )
