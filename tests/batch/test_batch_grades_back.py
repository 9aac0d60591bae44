"""Grades back into the course platforms: Canvas's gradebook import and Re-Upload zip, Moodle's grading
worksheet, gradebook import and feedback zip (grader/batch/exports.py and the modules it calls).

Each file is compared cell by cell with a hand-built expected file (tests/data/batch/grades_back/) for a
class holding a late student (the score after the penalty), a held student, a roster student who never
submitted, an invalid and a timed-out submission, and names with commas, quotes, formula characters and
accents. The zips are also read back the way Canvas and Moodle place an entry (their own parsing rules),
so a name that would hand one student's report to another is caught whatever the expected file says.
The wrong exporters of tests/data/batch/wrong_exports.py each make a test fail.
"""

from __future__ import annotations

import csv
import importlib.util
import io
import re
import zipfile
from pathlib import Path

import pytest

from grader.batch import canvas_export, moodle_export, posted
from grader.batch.exports import write_exports
from grader.batch.identity import Identity
from grader.batch.names import student_stem

DATA = Path(__file__).resolve().parents[1] / "data" / "batch"
EXPECTED = DATA / "grades_back"
TITLE = "Week 3 (4411)"
GRADED_AT = "2026-11-20T10:00:00+00:00"
HOSTILE_NAME = '=HYPERLINK("http://x","y")'

# (id, name, login, sis id, section, status, score, Canvas file of the download) per student; the
# roster student 45678 / 1004 has no result
CANVAS = [("12345", "Doe, Jane", "jdoe", "S001", "CS101-01", "graded", 8.5,
           "doejane_12345_987001_go_to_goal.py"),
          ("23456", HOSTILE_NAME, "+evil", "-1", "@sec", "graded", 10.0, "hyperlinkhttpxy_23456_987100_a.py"),
          ("34567", 'Łukasz "Luke" Żółć', "luke", "", "CS101-02", "held", 0.0,
           "lukaszlukezolc_LATE_34567_987200_qb_supervisor.py"),
          ("56789", "Smith_2024 ../../etc", "", "", "", "invalid", 0.0,
           "smith2024etc_56789_987300_notes.txt"),
          ("67890", "Tim Out", "", "", "", "timeout", 0.0, "timout_67890_987400_go_to_goal.py")]
ROSTER_ONLY = ("45678", "O'Brien, Seán", "sobrien", "S004", "CS101-02")
MOODLE_IDS = {"12345": "1001", "23456": "1002", "34567": "1003", "45678": "1004", "56789": "1005",
              "67890": "1006"}


def load_wrong():
    spec = importlib.util.spec_from_file_location("wrong_exports", DATA / "wrong_exports.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def result(identity: Identity, status: str, score: float) -> dict:
    value = {"week": 3, "status": status, "score": score, "max_score": 10.0 if status == "graded" else None,
             "seed": 7, "hidden": True, "checks": [], "message": "",
             "batch": {"student": identity.id, "identity": identity.to_json()},
             "timing": {"graded_at": GRADED_AT}}
    if identity.name == "Doe, Jane" or identity.name == "Jane Doe":     # 1.5 points late: 10 -> 8.5
        value["late"] = {"deadline": "2026-11-19T23:59:00+00:00", "submitted_at": "2026-11-20T09:00:00+00:00",
                         "seconds_late": 32460, "extension_until": None, "penalty_percent": 15.0,
                         "penalty_points": 1.5, "score_before": 10.0, "note": "1 day late"}
    return value


def klass(platform: str) -> tuple[dict[str, dict], list[Identity], list[str]]:
    """(results by student id, roster, missing) of the test class as a Canvas or a Moodle download gave it."""
    results, roster = {}, []
    for sid, name, login, sis, section, status, score, file in CANVAS:
        if platform == "canvas":
            who = Identity(id=sid, name=name, login=login, sis_id=sis, section=section, platform="canvas",
                           platform_id=sid, files=(file,))
        else:
            pid = MOODLE_IDS[sid]
            who = Identity(id=pid, name="Jane Doe" if sid == "12345" else name, login=login, sis_id=sis,
                           section=section, platform="moodle", platform_id=pid)
        results[who.id] = result(who, status, score)
        roster.append(who)
    sid, name, login, sis, section = ROSTER_ONLY
    missing_id = sid if platform == "canvas" else MOODLE_IDS[sid]
    roster.append(Identity(id=missing_id, name=name, login=login, sis_id=sis, section=section,
                           platform=platform, platform_id=missing_id))
    return results, roster, [missing_id]


def export(out: Path, platform: str) -> dict[str, bytes]:
    """Write the class's exports into ``out`` (with each report page); returns the pages by student id."""
    results, roster, missing = klass(platform)
    stems = {sid: student_stem(sid) for sid in results}
    pages = {}
    for sid in results:
        pages[sid] = f"<html><body>report of {sid}</body></html>".encode()
        (out / f"{stems[sid]}.html").write_bytes(pages[sid])
    record = write_exports(out, results, stems, week=3, title=TITLE, roster=roster, missing=missing)
    assert record["canvas_import.csv"]["rows"] == 6
    return pages


def cell_differences(expected: Path, written: Path) -> list[str]:
    """Every cell that differs, as ``row r, column c: expected X, written Y`` (and rows missing)."""
    want = list(csv.reader(io.StringIO(expected.read_text(encoding="utf-8"))))
    got = list(csv.reader(io.StringIO(written.read_text(encoding="utf-8"))))
    problems = [f"{len(want)} rows expected, {len(got)} written"] if len(want) != len(got) else []
    for r, (a, b) in enumerate(zip(want, got, strict=False)):
        for c in range(max(len(a), len(b))):
            x, y = (a[c] if c < len(a) else None), (b[c] if c < len(b) else None)
            if x != y:
                problems.append(f"row {r + 1}, column {c + 1} ({want[0][c] if c < len(want[0]) else '?'}): "
                                f"expected {x!r}, written {y!r}")
    return problems


def canvas_owner(entry: str) -> str | None:
    """The user id Canvas reads from a Re-Upload entry: the first all-digit `_` part of its file name
    (Assignment#infer_comment_context_from_filename), or None (skipped) without a second (the file id)."""
    digits = [p for p in entry.rsplit("/", 1)[-1].split("_") if re.fullmatch(r"\d+", p)]
    return digits[0] if len(digits) >= 2 else None


def moodle_owner(entry: str) -> str | None:
    """The participant id Moodle reads from a feedback-zip entry (importziplib.php: the first path part
    that explodes on `_` into at least 4 pieces with a numeric second piece)."""
    for part in entry.split("/")[:-1] or []:
        info = part.split("_", 4)
        if len(info) >= 4 and info[1].isdigit():
            return info[1]
    return None


def zip_problems(path: Path, listing: Path, pages: dict[str, bytes], owner) -> list[str]:
    """Differences between a feedback zip and its expected listing (``<id> <entry>`` lines), and entries
    the platform would give to someone else than the student whose report they hold."""
    expected = dict(line.split(" ", 1) for line in listing.read_text(encoding="utf-8").splitlines())
    problems = []
    with zipfile.ZipFile(path) as archive:
        entries = {info.filename: archive.read(info) for info in archive.infolist()}
    if sorted(entries) != sorted(expected.values()):
        problems.append(f"entries {sorted(entries)} != expected {sorted(expected.values())}")
    for sid, name in expected.items():
        if name in entries and entries[name] != pages[sid]:
            problems.append(f"{name}: not {sid}'s report")
    for name in entries:
        if owner(name) not in expected or entries[name] != pages[owner(name)]:
            problems.append(f"{name}: the platform gives it to {owner(name)!r}, whose report it is not")
        if ".." in name.split("/") or any(ord(c) < 32 for c in name) or len(name) > 200:
            problems.append(f"{name}: not a safe name")
    return problems


def test_canvas_import_and_feedback_zip_cell_by_cell(tmp_path: Path) -> None:
    pages = export(tmp_path, "canvas")
    assert cell_differences(EXPECTED / "canvas_import.csv", tmp_path / "canvas_import.csv") == []
    assert zip_problems(tmp_path / "canvas_feedback.zip", EXPECTED / "canvas_feedback.txt", pages,
                        canvas_owner) == []


def test_moodle_worksheet_gradebook_and_feedback_zip_cell_by_cell(tmp_path: Path) -> None:
    pages = export(tmp_path, "moodle")
    for name in ("moodle_grading_worksheet.csv", "moodle_gradebook.csv"):
        assert cell_differences(EXPECTED / name, tmp_path / name) == [], name
    assert zip_problems(tmp_path / "moodle_feedback.zip", EXPECTED / "moodle_feedback.txt", pages,
                        moodle_owner) == []


def test_why_each_blank_is_recorded(tmp_path: Path) -> None:
    results, roster, missing = klass("canvas")
    record = write_exports(tmp_path, results, {s: student_stem(s) for s in results}, week=3, roster=roster,
                           missing=missing)
    blank = record["canvas_import.csv"]["blank"]
    assert sorted(blank) == ["34567", "45678", "67890"]
    assert blank["34567"].startswith("held") and blank["45678"] == "on the roster, no submission"
    assert record["canvas_import.csv"]["title"] == "Autograder week 3"      # the default column title


def test_a_class_folder_is_matched_by_sis_user_id(tmp_path: Path) -> None:
    """A class folder's id is the institution's: it goes in SIS User ID, the Canvas ID stays empty, and
    neither zip holds an entry its platform could not place."""
    who = Identity(id="s1234567", name="Ann Lee")
    results = {"s1234567": result(who, "graded", 7.25)}
    (tmp_path / "s1234567.html").write_text("<p>r</p>")
    record = write_exports(tmp_path, results, {"s1234567": "s1234567"}, week=3, title=TITLE)
    rows = list(csv.reader(io.StringIO((tmp_path / "canvas_import.csv").read_text(encoding="utf-8"))))
    assert rows[2] == ["Ann Lee", "", "s1234567", "", "", "7.25"]
    assert record["canvas_feedback.zip"] == {"entries": 0, "not_included_count": 1, "not_included": {
        "s1234567": "no file of a Canvas download to attach the report to"}}
    assert record["moodle_feedback.zip"]["not_included"] == {"s1234567": "no Moodle participant id"}
    assert (tmp_path / "moodle_grading_worksheet.csv").read_text().count("\n") == 1     # the header only


def test_hostile_names_make_safe_bounded_entries() -> None:
    for name in ("../../x", "a/b\\c", "\x1b[2J\x00", "_".join(["9"] * 80), "x" * 5000, "..", "12_34_56"):
        who_c = Identity(id="77", name=name, platform="canvas", platform_id="77", files=("n_77_555_f.py",))
        who_m = Identity(id="88", name=name, platform="moodle", platform_id="88")
        entry = canvas_export.entry_name(who_c)
        folder = moodle_export.folder_name(who_m)
        assert canvas_owner(entry) == "77" and moodle_owner(folder + "/feedback.html") == "88", (name, entry)
        for text in (entry, folder):
            assert "/" not in text and ".." not in text and text.isprintable() and len(text) <= 120, text


@pytest.mark.parametrize("wrong, target, platform", [
    ("canvas_csv_without_points_possible", (canvas_export, "canvas_csv"), "canvas"),
    ("posted_before_penalty", (posted, "posted"), "canvas"),
    ("posted_before_penalty", (posted, "posted"), "moodle"),
    ("posted_zero_when_blank", (posted, "posted"), "canvas"),
    ("moodle_folder_with_raw_name", (moodle_export, "folder_name"), "moodle"),
    ("canvas_entry_with_raw_name", (canvas_export, "entry_name"), "canvas"),
])
def test_each_wrong_exporter_is_caught(wrong: str, target, platform: str, tmp_path: Path,
                                       monkeypatch) -> None:
    module, name = target
    monkeypatch.setattr(module, name, getattr(load_wrong(), wrong))
    pages = export(tmp_path, platform)
    if platform == "canvas":
        problems = (cell_differences(EXPECTED / "canvas_import.csv", tmp_path / "canvas_import.csv")
                    + zip_problems(tmp_path / "canvas_feedback.zip", EXPECTED / "canvas_feedback.txt", pages,
                                   canvas_owner))
    else:
        problems = (cell_differences(EXPECTED / "moodle_grading_worksheet.csv",
                                     tmp_path / "moodle_grading_worksheet.csv")
                    + zip_problems(tmp_path / "moodle_feedback.zip", EXPECTED / "moodle_feedback.txt", pages,
                                   moodle_owner))
    assert problems, f"{wrong} was not caught"
