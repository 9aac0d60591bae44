"""Gradescope's "Export Submissions": ``submission_metadata.yml`` and one ``submission_<id>/`` folder per
submission (sometimes inside ``assignment_<id>_export/``).

The metadata maps each folder name to its ``:submitters:`` (``:name:``, ``:sid:``, ``:email:``; several for
a group) and ``:created_at:`` (Ruby's YAML: symbol keys keep their colon). It is read with PyYAML's safe
loader, capped in size, and only the fields named here are taken, each bounded (an alias or a huge value
costs nothing more). Each submitter is a student, id = SID, else e-mail, else the submission's folder name.
One student in several submissions: the latest ``created_at`` wins and the others are reported; without
two distinct times the student is held, never guessed.
"""

from __future__ import annotations

import dataclasses
import re
from datetime import datetime

import yaml

from grader.batch.export_files import Export, ExportRefused, read_metadata
from grader.batch.found import Found, rel_clashes
from grader.batch.identity import Identity

METADATA = "submission_metadata.yml"
FOLDER = re.compile(r"^submission_\d{1,20}$")
MAX_SUBMISSIONS = 20_000
MAX_SUBMITTERS = 50


def metadata_name(export: Export) -> str | None:
    """Where the metadata file is: at the top, or inside the one wrapping folder."""
    names = {e.name for e in export.entries}
    if METADATA in names:
        return METADATA
    wrapped = [n for n in names if n.count("/") == 1 and n.endswith("/" + METADATA)]
    return wrapped[0] if len(wrapped) == 1 else None


def _field(value: dict, key: str) -> object:
    """A field by its Ruby-symbol key (``:sid``) or a plain one (``sid``)."""
    return value.get(f":{key}", value.get(key))


def _text(value: object) -> str:
    if isinstance(value, bool) or value is None:
        return ""
    return str(value)[:200].strip() if isinstance(value, (str, int)) else ""


def _time(value: object) -> str:
    """``created_at`` as ISO 8601 with its offset; "" when missing or without an offset."""
    if isinstance(value, str):
        text = value.strip()[:64]
        for form in ("%Y-%m-%d %H:%M:%S.%f %z", "%Y-%m-%d %H:%M:%S %z"):
            try:
                value = datetime.strptime(re.sub(r"(\.\d{6})\d+", r"\1", text), form)
                break
            except ValueError:
                continue
        else:
            try:
                value = datetime.fromisoformat(text)
            except ValueError:
                return ""
    if not isinstance(value, datetime) or value.tzinfo is None:
        return ""
    return value.isoformat()


def read_gradescope(export: Export) -> tuple[dict[str, Found], list[str], list[str]]:
    """Students by id, the entries that could not be placed, and what the instructor should know
    (resubmissions resolved). ExportRefused when the metadata cannot be read."""
    meta_name = metadata_name(export)
    assert meta_name is not None, "read_gradescope is called on a Gradescope export"
    base = meta_name[: -len(METADATA)]
    try:
        data = yaml.safe_load(read_metadata(export, meta_name))
    except (yaml.YAMLError, RecursionError, ValueError) as exc:
        raise ExportRefused(f"{meta_name} cannot be read as YAML ({str(exc)[:300]})") from None
    if not isinstance(data, dict) or len(data) > MAX_SUBMISSIONS:
        raise ExportRefused(f"{meta_name} is not a map of at most {MAX_SUBMISSIONS} submissions")
    folders: dict[str, list[tuple[str, str]]] = {}
    unplaced: list[str] = []
    for entry in export.entries:
        if entry.name == meta_name:
            continue
        inside = entry.name[len(base) :] if entry.name.startswith(base) else ""
        folder, _, rel = inside.partition("/")
        if FOLDER.match(folder) and rel:
            folders.setdefault(folder, []).append((entry.name, rel))
        else:
            unplaced.append(entry.name)
    students: dict[str, Found] = {}
    times: dict[str, str] = {}
    notes: list[str] = []
    for key in sorted(k for k in data if isinstance(k, str) and FOLDER.match(k)):
        value = data[key] if isinstance(data[key], dict) else {}
        created = _time(_field(value, "created_at"))
        submitters = _field(value, "submitters")
        for person in (submitters if isinstance(submitters, list) else [])[:MAX_SUBMITTERS]:
            person = person if isinstance(person, dict) else {}
            sid, email = _text(_field(person, "sid")), _text(_field(person, "email"))
            ident = Identity(
                id=sid or email or key,
                name=_text(_field(person, "name")),
                login=email,
                sis_id=sid,
                platform="gradescope",
                platform_id=key.split("_", 1)[1],
                submitted_at=created,
            )
            found = Found(ident, members=list(folders.get(key, [])))
            for name, _rel in found.members:
                found.add_file_name(name)
            if not found.members:
                found.hold(f"the export has no files in {key}/ for this submission")
            earlier = students.get(ident.id)
            if earlier is not None:
                found = _latest(earlier, found, times.get(ident.id, ""), created, notes)
            students[ident.id], times[ident.id] = found, found.identity.submitted_at
    unplaced += [f"{base}{k}/ (not in {METADATA})" for k in sorted(set(folders) - set(data))]
    for found in students.values():
        rel_clashes(found)
    return students, unplaced, notes


def _latest(earlier: Found, later: Found, t_earlier: str, t_later: str, notes: list[str]) -> Found:
    """The student's newest submission of two; held when their times do not tell."""
    sid = later.identity.id
    ids = f"{earlier.identity.platform_id} and {later.identity.platform_id}"
    if not t_earlier or not t_later or t_earlier == t_later:
        earlier.hold(f"two submissions ({ids}) and no distinct submission times to tell which is the latest")
        return earlier
    newest, older = (
        (later, earlier)
        if datetime.fromisoformat(t_later) > datetime.fromisoformat(t_earlier)
        else (earlier, later)
    )
    notes.append(
        f"{sid}: resubmitted; graded submission {newest.identity.platform_id} "
        f"({newest.identity.submitted_at}), not {older.identity.platform_id}"
    )
    return dataclasses.replace(newest, held=newest.held or "")
