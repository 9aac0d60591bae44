"""Issue 29's round trip, end to end with the real grader: a platform's own download goes in through one
`grade` command (roster, deadline, late policy), and every number of the files that go back to the
platform is checked: Canvas's import CSV and Re-Upload zip, Moodle's grading worksheet and feedback zip,
Gradescope's results.json. Week 3: the reference solution earns 12.5 of 12.5 (hidden checks included,
the official default), the handout's stub 0.

Canvas: on time; 26 hours late at 10 %/day (2 days: 2.5 points off); late but with a 2-day extension on
the roster (no penalty); on the roster and never submitted (blank); a resubmission (Canvas renamed the
file go_to_goal-1.py); a stub. Moodle: on time, late, a stub, a worksheet student who never submitted.
Gradescope: a student's two submissions (the later one graded, 30 minutes late at 2 %/hour with 15
minutes of grace: one hour, 0.25 points off) and a stub.
"""

from __future__ import annotations

import csv
import io
import json
import zipfile
from pathlib import Path

import pytest
from batch_helpers import make_zip

from grader.batch.names import student_stem
from grader.cli import main

ROOT = Path(__file__).resolve().parents[2]
SOLUTION = {p.name: p.read_text() for p in sorted((ROOT / "solutions" / "week3").glob("*.py"))}
STUB = {p.name: p.read_text() for p in sorted((ROOT / "assignments" / "week3").glob("*.py"))}
pytest.importorskip("grader.grading")


def grade(*words: str) -> int:
    return main(["week3", "--quiet", "--jobs", "2", "--seed", "29", *words])


def rows_of(path: Path) -> list[list[str]]:
    return list(csv.reader(io.StringIO(path.read_text(encoding="utf-8"))))


def entries_of(path: Path) -> dict[str, bytes]:
    with zipfile.ZipFile(path) as archive:
        return {info.filename: archive.read(info) for info in archive.infolist()}


def canvas_download(path: Path) -> Path:
    entries: dict[str, str] = {}
    for person, files in (("doejane_101", SOLUTION), ("smithjohn_LATE_102", SOLUTION),
                          ("leeann_LATE_103", SOLUTION), ("kimlee_105", SOLUTION), ("stubby_106", STUB)):
        for number, (name, text) in enumerate(files.items()):
            shown = "go_to_goal-1.py" if person == "kimlee_105" and name == "go_to_goal.py" else name
            entries[f"{person}_{int(person[-3:]) * 100 + number}_{shown}"] = text
    return make_zip(path, entries)


def test_canvas_download_to_canvas_import_and_feedback_zip(tmp_path: Path) -> None:
    export = canvas_download(tmp_path / "CS101-HW3_submissions.zip")
    (tmp_path / "roster.csv").write_text(
        "Student,ID,SIS User ID,SIS Login ID,Section,Extension\n    Points Possible,,,,,\n"
        '"Doe, Jane",101,S1,jdoe,A,\n"Smith, John",102,S2,jsmith,A,\n"Lee, Ann",103,S3,alee,B,2d\n'
        '"Never, Came",104,S4,ncame,B,\n"Lee, Kim",105,S5,klee,A,\n"=cmd|calc, Stub",106,S6,@stub,A,\n')
    (tmp_path / "times.csv").write_text(
        "id,submitted_at\n101,2026-03-01T23:00:00-05:00\n102,2026-03-03T01:59:00-05:00\n"
        "103,2026-03-03T12:00:00-05:00\n105,2026-03-01T20:00:00-05:00\n106,2026-03-01T21:00:00-05:00\n")
    out = tmp_path / "graded"
    policy = ["--roster", str(tmp_path / "roster.csv"), "--times", str(tmp_path / "times.csv"),
              "--deadline", "2026-03-01T23:59-05:00", "--late-penalty", "10%/day", "--late-cap", "50%"]
    title = ["--canvas-assignment", "HW 3 (4411)"]
    assert grade("--batch", str(export), "--out", str(out), *policy, *title) == 0
    assert rows_of(out / "canvas_import.csv") == [
        ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "HW 3 (4411)"],
        ["    Points Possible", "", "", "", "", "12.5"],
        ["Doe, Jane", "101", "S1", "jdoe", "A", "12.5"],
        ["Smith, John", "102", "S2", "jsmith", "A", "10"],          # 26 h late: 2 days at 10 %
        ["Lee, Ann", "103", "S3", "alee", "B", "12.5"],             # late, within her extension
        ["Never, Came", "104", "S4", "ncame", "B", ""],             # never submitted: blank, not 0
        ["Lee, Kim", "105", "S5", "klee", "A", "12.5"],             # the resubmitted file graded
        ["'=cmd|calc, Stub", "106", "S6", "'@stub", "A", "0"]]      # the stub
    zipped = entries_of(out / "canvas_feedback.zip")
    expected = {"101": "doejane_101_10100", "102": "smithjohn_102_10200", "103": "leeann_103_10300",
                "105": "leekim_105_10500", "106": "cmdcalcstub_106_10600"}
    assert sorted(zipped) == sorted(f"{v}_feedback.html" for v in expected.values())
    for sid, stem in expected.items():
        assert zipped[f"{stem}_feedback.html"] == (out / f"{sid}.html").read_bytes(), sid
    assert b"Late penalty: 2.5 points" in zipped["smithjohn_102_10200_feedback.html"]
    record = json.loads((out / "batch.json").read_text())
    assert record["hidden"] is True and record["exports"]["canvas_import.csv"]["blank"] == {
        "104": "on the roster, no submission"}

    # the late policy changes: nobody is graded again, 102's score follows and the change is said
    assert grade("--batch", str(export), "--out", str(out), *policy[:-4], "--late-penalty", "5%/day",
                 *title) == 0
    assert rows_of(out / "canvas_import.csv")[3][5] == "11.25"
    record = json.loads((out / "batch.json").read_text())
    assert record["this_run"]["graded_now"] == 0
    assert record["changed"] == [{"student": "102", "before": 10.0, "after": 11.25,
                                  "status_before": "graded", "status_after": "graded",
                                  "reasons": ["late policy"], "at": record["changed"][0]["at"],
                                  "this_run": True}]        # changed by this run, though not graded again
    kept = [json.loads(p.read_text()) for p in (out / "history" / "102").glob("*.json")]
    assert [k["score"] for k in kept] == [10.0]


def test_moodle_download_to_worksheet_and_feedback_zip(tmp_path: Path) -> None:
    entries = {}
    for folder, files in (("Jane Doe_501", SOLUTION), ("John Smith_502", SOLUTION), ("Stu B_503", STUB)):
        for name, text in files.items():
            entries[f"{folder}_assignsubmission_file/week3/{name}"] = text
    export = make_zip(tmp_path / "CS101-HW3-77.zip", entries)
    (tmp_path / "worksheet.csv").write_text(
        "Identifier,Full name,Email address,Status,Grade,Maximum Grade,Grade can be changed,"
        "Last modified (submission),Last modified (grade),Feedback comments\n"
        "Participant 501,Jane Doe,jane@uni.edu,Submitted for grading,,12.50,Yes,"
        '"Sunday, 1 March 2026, 11:00 PM",-,\n'
        "Participant 502,John Smith,john@uni.edu,Submitted for grading - 1 day 2 hours late,,12.50,Yes,"
        '"Tuesday, 3 March 2026, 1:59 AM",-,\n'
        "Participant 503,Stu B,stu@uni.edu,Submitted for grading,,12.50,Yes,"
        '"Sunday, 1 March 2026, 9:00 PM",-,\n'
        "Participant 504,Kim Park,kim@uni.edu,No submission,,12.50,Yes,-,-,\n")
    sheet = str(tmp_path / "worksheet.csv")
    out = tmp_path / "graded"
    assert grade("--batch", str(export), "--out", str(out), "--roster", sheet, "--times", sheet,
                 "--timezone", "America/New_York", "--deadline", "2026-03-01T23:59",
                 "--late-penalty", "10%/day") == 0
    when = {sid: json.loads((out / f"{sid}.json").read_text())["timing"]["graded_at"]
            for sid in ("501", "502", "503")}
    words = "The full report is the attached feedback file."
    assert rows_of(out / "moodle_grading_worksheet.csv") == [
        ["Identifier", "Full name", "Email address", "Grade", "Maximum Grade", "Last modified (grade)",
         "Feedback comments"],
        ["Participant 501", "Jane Doe", "jane@uni.edu", "12.5", "12.5", when["501"],
         f"Autograder score 12.5 / 12.5. {words}"],
        ["Participant 502", "John Smith", "john@uni.edu", "10", "12.5", when["502"],
         f"Autograder score 10 / 12.5 after a late penalty of 2.5 points. {words}"],
        ["Participant 503", "Stu B", "stu@uni.edu", "0", "12.5", when["503"],
         f"Autograder score 0 / 12.5. {words}"],
        ["Participant 504", "Kim Park", "kim@uni.edu", "", "12.5", "-", ""]]
    zipped = entries_of(out / "moodle_feedback.zip")
    folders = {"501": "Jane Doe", "502": "John Smith", "503": "Stu B"}
    names = {pid: f"{name}_{pid}_assignsubmission_file_/feedback.html" for pid, name in folders.items()}
    assert sorted(zipped) == sorted(names.values())
    for pid, name in names.items():
        assert zipped[name] == (out / f"{pid}.html").read_bytes(), pid
    assert rows_of(out / "moodle_gradebook.csv")[1:] == [["jane@uni.edu", "", "Jane Doe", "12.5"],
                                                          ["john@uni.edu", "", "John Smith", "10"],
                                                          ["stu@uni.edu", "", "Stu B", "0"]]


def test_gradescope_export_to_results_json(tmp_path: Path) -> None:
    base = "assignment_77_export/"
    metadata = (
        "submission_9001:\n  :submitters:\n  - :name: Jane Doe\n    :sid: '1001'\n    :email: jane@uni.edu\n"
        "  :created_at: 2026-03-01 23:58:10.123456000 -05:00\n"
        "submission_9003:\n  :submitters:\n  - :name: Jane Doe\n    :sid: '1001'\n    :email: jane@uni.edu\n"
        "  :created_at: 2026-03-02 00:30:00.000000000 -05:00\n"
        "submission_9004:\n  :submitters:\n  - :name: Ann Lee\n    :sid: '1004'\n    :email: ann@uni.edu\n"
        "  :created_at: 2026-03-01 10:00:00 -05:00\n")
    files = {f"{base}submission_metadata.yml": metadata}
    for folder, code in (("submission_9001", STUB), ("submission_9003", SOLUTION), ("submission_9004", STUB)):
        files.update({f"{base}{folder}/{name}": text for name, text in code.items()})
    export = make_zip(tmp_path / "export.zip", files)
    out = tmp_path / "graded"
    assert grade("--batch", str(export), "--out", str(out), "--deadline", "2026-03-02T00:00-05:00",
                 "--late-penalty", "2%/hour", "--grace", "15m") == 0
    jane = json.loads((out / "gradescope" / student_stem("1001") / "results.json").read_text())
    ann = json.loads((out / "gradescope" / student_stem("1004") / "results.json").read_text())
    assert (jane["score"], sum(t["score"] for t in jane["tests"])) == (12.25, 12.5)   # 9003: 1 h late
    assert (ann["score"], sum(t["max_score"] for t in ann["tests"])) == (0.0, 12.5)
    assert [r[5] for r in rows_of(out / "canvas_import.csv")[1:]] == ["12.5", "12.25", "0"]
