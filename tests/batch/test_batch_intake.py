"""Platform downloads as ``--batch`` input, as the platforms make them: Canvas's submissions zip (and its
extracted folder), Moodle's download (folders, pre-4.1 folders, flat), Gradescope's export; the roster,
submission times, the late policy and held students, end to end with the fake grader."""

from __future__ import annotations

import csv
import importlib.util
import io
import json
import os
import zipfile
from pathlib import Path

import pytest
from batch_helpers import make_zip

from grader.batch import canvas_download
from grader.batch.export_files import list_export
from grader.batch.intake import IntakeError, IntakeOptions, read_class
from grader.batch.names import student_stem
from grader.batch.runner import BatchOptions, run_batch
from grader.batch.submissions import read_submission

FAKE = "batch_fake_grader:fake_grade"
COUNT = "batch_fake_grader:count_calls"
DEADLINE = "2026-03-01T23:59-05:00"


def _wrong() -> object:
    path = Path(__file__).parents[1] / "data" / "batch" / "wrong_intake.py"
    spec = importlib.util.spec_from_file_location("wrong_intake", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _zip_bytes(entries: dict[str, str]) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        for name, text in entries.items():
            archive.writestr(name, text)
    return buffer.getvalue()


def canvas_export(path: Path) -> Path:
    """A Canvas "Download Submissions" zip as canvas-lms content_zipper.rb names its entries."""
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("doejane_101_9001_answer.txt", "score 10\n")  # on time
        archive.writestr("smithjohn_LATE_102_9002_answer.txt", "score 6\n")  # 26 h late
        archive.writestr("leeann_late_103_9003_answer.txt", "score 7\n")  # late, has an extension
        archive.writestr("parkkim_LATE_104_9004_answer.txt", "score 8\n")  # late, no time given
        archive.writestr("stranger_106_9006_answer.txt", "score 5\n")  # not on the roster
        archive.writestr("kimlee_109_9009_week3.zip", _zip_bytes({"week3/answer.txt": "score 9\n"}))
        archive.writestr("texter_110_text.html", "<p>my answer</p>")  # a text entry only
        archive.writestr("../evil_111_9011_answer.txt", "score 10\n")  # zip slip
        archive.writestr("twice_112_9012_answer.txt", "score 1\n")  # two entries, one file
        archive.writestr("twice_112_9013_ANSWER.txt", "score 2\n")
        archive.writestr("stub_113_9013_answer.txt", "score 0\n")  # a stub
    return path


ROSTER = (
    "Student,ID,SIS User ID,SIS Login ID,Section,HW3 (1)\n    Points Possible,,,,,10\n"
    '"Doe, Jane",101,S1,jdoe,A,\n"Smith, John",102,S2,jsmith,A,\n"Lee, Ann",103,S3,alee,B,\n'
    '"Park, Kim",104,S4,kpark,B,\n"Never, Came",105,S5,ncame,B,\n"Student, Test",999,,,,\n'
    '"Lee, Kim",109,S9,klee,A,\n"Text, Er",110,S10,ter,A,\n"Twice, T",112,S12,tt,A,\n'
    '"Stub, S",113,S13,ss,A,\n'
)


def test_canvas_download_end_to_end(tmp_path: Path, monkeypatch) -> None:
    export = canvas_export(tmp_path / "CS101-HW3_submissions.zip")
    (tmp_path / "roster.csv").write_text(
        ROSTER.replace('"Lee, Ann",103,S3,alee,B,', '"Lee, Ann",103,S3,alee,B,')
        .replace("Section,HW3 (1)", "Section,Extension")
        .replace('"Lee, Ann",103,S3,alee,B,', '"Lee, Ann",103,S3,alee,B,2d')
    )
    (tmp_path / "times.csv").write_text(
        "id,submitted_at\n101,2026-03-01T23:00:00-05:00\n"
        "102,2026-03-03T01:59:00-05:00\n103,2026-03-03T12:00:00-05:00\n"
    )
    intake = IntakeOptions(
        roster=tmp_path / "roster.csv",
        times=tmp_path / "times.csv",
        deadline=DEADLINE,
        late_penalty="10%/day",
        late_cap="50%",
    )
    out = tmp_path / "out"
    calls = tmp_path / "calls"
    monkeypatch.setenv("BATCH_CALLS", str(calls))
    stream = io.StringIO()
    report = run_batch(
        BatchOptions(week=3, batch_dir=export, out=out, seed=3, jobs=1, intake=intake),
        grade_fn=COUNT,
        stream=stream,
    )
    said = stream.getvalue()
    assert said.startswith('reading Canvas "Download Submissions": CS101-HW3_submissions.zip'), said[:200]
    assert report["layout"] == "canvas" and report["counts"] == {
        "graded": 7,
        "invalid": 1,
        "held": 1,
        "timeout": 0,
        "crashed": 0,
    }
    results = {sid: json.loads((out / f"{sid}.json").read_text()) for sid in report["per_student"]}
    late = {sid: (r["score"], r["late"]["penalty_points"]) for sid, r in results.items() if r.get("late")}
    assert late == {
        "101": (10.0, 0.0),
        "102": (4.0, 2.0),
        "103": (7.0, 0.0),
        "104": (8.0, 0.0),
        "106": (5.0, 0.0),
        "109": (9.0, 0.0),
        "113": (0.0, 0.0),
    }, late
    assert (
        results["102"]["late"]["seconds_late"] == 26 * 3600 and results["102"]["late"]["score_before"] == 6.0
    )
    assert results["103"]["late"]["extension_until"] == "2026-03-03T23:59:00-05:00"
    assert results["104"]["late"]["note"] == "marked late by Canvas, no submission time: give --times"
    assert "104: marked late by Canvas, no submission time: give --times" in said
    identity = results["102"]["batch"]["identity"]
    assert (
        identity["id"],
        identity["name"],
        identity["login"],
        identity["section"],
        identity["sis_id"],
        identity["platform"],
        identity["late_flag"],
    ) == ("102", "Smith, John", "jsmith", "A", "S2", "canvas", True)
    assert results["103"]["batch"]["identity"]["late_flag"] is True  # "late" in lower case too
    assert results["110"]["status"] == "invalid" and "text entry" in " ".join(results["110"]["notices"])
    assert results["112"]["status"] == "held" and results["112"]["score"] is None
    assert "twice_112_9012_answer.txt" in results["112"]["message"]
    page = (out / "112.html").read_text()
    assert "being sorted out" in page and "submit again" not in page and "twice_112" not in page
    assert report["missing"] == ["105"] and [r["id"] for r in report["roster"]] == [
        "101",
        "102",
        "103",
        "104",
        "105",
        "109",
        "110",
        "112",
        "113",
    ]  # no points row, no test student
    assert report["intake"]["not_on_roster"] == ["106"]
    assert report["intake"]["unplaced"] and "points outside" in report["intake"]["unplaced"][0]
    rows = {r["student"]: r for r in csv.DictReader((out / "gradebook.csv").open())}
    assert (rows["102"]["total"], rows["102"]["late_penalty"], rows["102"]["score_before_penalty"]) == (
        "4.0",
        "2.0",
        "6.0",
    )
    assert (rows["105"]["status"], rows["105"]["total"]) == ("missing", "")
    assert (rows["112"]["status"], rows["112"]["total"]) == ("held", "")
    summary = (out / "summary.html").read_text()
    for text in (
        "On the roster, no submission (1)",
        "Not on the roster (graded) (1)",
        "Held: yours to sort out",
        "(late: &minus;2)",
        "10% per day late, at most 50%",
    ):
        assert text in summary, text
    assert "Late penalty: 2 points" in (out / "102.html").read_text()
    graded_once = sorted(calls.read_text().split())

    # a new policy: no student code runs again (only the held student is looked at again), scores and
    # pages follow it
    calls.write_text("")
    again = run_batch(
        BatchOptions(
            week=3,
            batch_dir=export,
            out=out,
            seed=3,
            jobs=1,
            quiet=True,
            intake=IntakeOptions(
                roster=tmp_path / "roster.csv",
                times=tmp_path / "times.csv",
                deadline=DEADLINE,
                late_penalty="5%/day",
            ),
        ),
        grade_fn=COUNT,
    )
    assert calls.read_text() == "" and graded_once == ["101", "102", "103", "104", "106", "109", "113"]
    assert again["per_student"]["102"]["score"] == 5.0
    assert "Late penalty: 1 point (10%" in (out / "102.html").read_text()
    assert "Late penalty: 2 points" not in (out / "102.html").read_text()
    # and without a policy the stored scores are the raw ones again
    run_batch(BatchOptions(week=3, batch_dir=export, out=out, seed=3, jobs=1, quiet=True), grade_fn=COUNT)
    stored = json.loads((out / "102.json").read_text())
    assert (
        stored["score"] == 6.0
        and "late" not in stored
        and "Late penalty" not in (out / "102.html").read_text()
    )


def test_canvas_names_and_the_extracted_folder(tmp_path: Path) -> None:
    export = canvas_export(tmp_path / "dl.zip")
    folder = tmp_path / "extracted" / "CS101 submissions"  # extracted into a wrapping folder
    folder.mkdir(parents=True)
    with zipfile.ZipFile(export) as archive:
        for info in archive.infolist():
            if ".." not in info.filename:
                (folder / info.filename).write_bytes(archive.read(info))
    from_zip, from_folder = read_class(export, IntakeOptions()), read_class(folder.parent, IntakeOptions())
    assert from_folder.layout == from_zip.layout == "canvas"
    assert [(s.id, s.kind, s.members) for s in from_zip.students] == [
        (s.id, s.kind, s.members) for s in from_folder.students
    ]
    nested = read_submission(next(s for s in from_folder.students if s.id == "109"), week=3)
    assert nested.files == {"answer.txt": b"score 9\n"} and nested.root == "week3"

    entries = {
        "doejane_101_1_go_to_goal-1.py": "x",
        "doejane_101_2_notes-1.txt": "y",  # re-upload
        "anon_a1B2c_3_go_to_goal.py": "x",
        "anon_A1b2C_11_go_to_goal.py": "x",  # another student: Canvas's anonymous ids are case-sensitive
        "LATE_anon_zz9_4_go_to_goal.py": "x",  # anonymous
        "both_7_5_go_to_goal.py": "x",
        "both_7_6_go_to_goal-1.py": "y",  # ambiguous
        "lee_LATE_8_9_my_2_file_3_.py": "z",
        "odd_late_9_10_a.py": "z",
    }
    canvas = read_class(make_zip(tmp_path / "names.zip", entries), IntakeOptions())
    by_id = {s.id: s for s in canvas.students}
    assert by_id["101"].members == (
        ("doejane_101_1_go_to_goal-1.py", "go_to_goal.py"),
        ("doejane_101_2_notes-1.txt", "notes-1.txt"),
    )
    assert by_id["anon_a1B2c"].identity.name == "" and by_id["anon_zz9"].identity.late_flag
    assert by_id["7"].kind == "held" and "go_to_goal" in by_id["7"].held
    assert by_id["8"].members == (("lee_LATE_8_9_my_2_file_3_.py", "my_2_file_3_.py"),)
    flags = {sid: s.identity.late_flag for sid, s in by_id.items()}
    assert flags == {
        "101": False,
        "anon_a1B2c": False,
        "anon_A1b2C": False,
        "anon_zz9": True,
        "7": False,
        "8": True,
        "9": True,
    }
    assert student_stem("anon_a1B2c") != student_stem("anon_A1b2C")  # two files, also case-insensitively
    # the wrong readers: one drops LATE, one knows only upper-case LATE; each misses a flag above
    export_listing = list_export(tmp_path / "names.zip")
    for wrong in (_wrong().CANVAS_ENTRY_IGNORING_LATE, _wrong().CANVAS_ENTRY_UPPER_LATE_ONLY):
        saved = canvas_download.ENTRY
        canvas_download.ENTRY = wrong
        try:
            found, _ = canvas_download.read_canvas(export_listing)
        finally:
            canvas_download.ENTRY = saved
        assert {sid: f.identity.late_flag for sid, f in found.items()} != flags


def moodle_entries(flat: bool) -> dict[str, str]:
    if flat:
        return {
            "Jane Doe_501_assignsubmission_file_answer.txt": "score 10\n",
            "John Smith_502_assignsubmission_file_answer.txt": "score 6\n",
            "John Smith_502_assignsubmission_onlinetext_onlinetext.html": "<p>hi</p>",
            "Participant_503_assignsubmission_file_answer.txt": "score 7\n",
        }
    return {
        "Jane Doe_501_assignsubmission_file/week3/answer.txt": "score 10\n",  # 4.1+
        "John Smith_502_assignsubmission_file_/answer.txt": "score 6\n",  # before 4.1
        "John Smith_502_assignsubmission_onlinetext/onlinetext.html": "<p>hi</p>",
        "Participant_503_assignsubmission_file/answer.txt": "score 7\n",
    }  # blind marking


WORKSHEET = (
    "Identifier,Full name,Email address,Status,Grade,Maximum Grade,Grade can be changed,"
    "Last modified (submission),Last modified (grade),Feedback comments\n"
    "Participant 501,Jane Doe,jane@uni.edu,Submitted for grading,,10.00,Yes,"
    '"Sunday, 1 March 2026, 11:00 PM",-,\n'
    "Participant 502,John Smith,john@uni.edu,Submitted for grading - 1 day 2 hours late,,10.00,Yes,"
    '"Tuesday, 3 March 2026, 1:59 AM",-,\n'
    "Participant 503,Ann Lee,ann@uni.edu,Submitted for grading,,10.00,Yes,-,-,\n"
    "Participant 504,Kim Park,kim@uni.edu,No submission,,10.00,Yes,-,-,\n"
)


def test_moodle_download_both_layouts(tmp_path: Path) -> None:
    folder = tmp_path / "moodle"
    for name, text in moodle_entries(flat=False).items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    layouts = {}
    for label, source in (
        ("folders", folder),
        ("flat zip", make_zip(tmp_path / "m.zip", moodle_entries(True))),
    ):
        klass = read_class(source, IntakeOptions())
        layouts[label] = {s.id: (s.identity.name, [rel for _n, rel in s.members]) for s in klass.students}
        assert klass.layout == "moodle", label
    assert layouts["folders"] == {
        "501": ("Jane Doe", ["week3/answer.txt"]),
        "502": ("John Smith", ["answer.txt"]),
        "503": ("", ["answer.txt"]),
    }
    assert layouts["flat zip"] == {
        "501": ("Jane Doe", ["answer.txt"]),
        "502": ("John Smith", ["answer.txt"]),
        "503": ("", ["answer.txt"]),
    }
    (tmp_path / "worksheet.csv").write_text(WORKSHEET)
    out = tmp_path / "out"
    intake = IntakeOptions(
        roster=tmp_path / "worksheet.csv",
        times=tmp_path / "worksheet.csv",
        timezone="America/New_York",
        deadline="2026-03-01T23:59",
        late_penalty="10%/day",
    )
    report = run_batch(
        BatchOptions(
            week=3, batch_dir=tmp_path / "m.zip", out=out, seed=3, jobs=1, quiet=True, intake=intake
        ),
        grade_fn=FAKE,
    )
    assert report["layout"] == "moodle" and report["missing"] == ["504"]
    results = {sid: json.loads((out / f"{sid}.json").read_text()) for sid in ("501", "502", "503")}
    assert [(r["score"], r["late"]["penalty_points"]) for r in results.values()] == [
        (10.0, 0.0),
        (4.0, 2.0),
        (7.0, 0.0),
    ]
    assert results["502"]["late"]["submitted_at"] == "2026-03-03T01:59:00-05:00"
    assert results["503"]["batch"]["identity"]["name"] == "Ann Lee"  # blind marking: the roster's
    assert results["503"]["late"]["note"].startswith("no submission time from moodle")
    assert "online text" in " ".join(results["502"]["notices"])
    with pytest.raises(IntakeError, match="local date; give --timezone"):
        read_class(tmp_path / "m.zip", IntakeOptions(times=tmp_path / "worksheet.csv"))


METADATA = """\
submission_9001:
  :submitters:
  - :name: Jane Doe
    :sid: '1001'
    :email: jane@uni.edu
  :created_at: 2026-03-01 23:58:10.123456000 -05:00
  :score: 8.5
submission_9002:
  :submitters:
  - :name: John Smith
    :sid: A-1
    :email: john@uni.edu
  - :name: Joan Smith
    :sid: a-1
    :email: joan@uni.edu
  :created_at: 2026-03-02 01:00:00.000000000 -05:00
submission_9003:
  :submitters:
  - :name: Jane Doe
    :sid: '1001'
    :email: jane@uni.edu
  :created_at: 2026-03-02 00:30:00.000000000 -05:00
submission_9004:
  :submitters:
  - :name: Ann Lee
    :email: ann@uni.edu
  :created_at: 2026-03-01 10:00:00 -05:00
submission_9005:
  :submitters:
  - :name: Ann Lee
    :email: ann@uni.edu
  :created_at: 2026-03-01 10:00:00 -05:00
"""


def test_gradescope_export(tmp_path: Path) -> None:
    base = "assignment_77_export/"
    files = {
        f"{base}submission_metadata.yml": METADATA,
        f"{base}submission_9001/answer.txt": "score 3\n",
        f"{base}submission_9003/answer.txt": "score 9\n",
        f"{base}submission_9002/week3/answer.txt": "score 6\n",
        f"{base}submission_9004/answer.txt": "score 1\n",
        f"{base}submission_9005/answer.txt": "score 2\n",
        f"{base}submission_9999/answer.txt": "score 10\n",
    }
    export = make_zip(tmp_path / "export.zip", files)
    out = tmp_path / "out"
    intake = IntakeOptions(deadline="2026-03-02T00:00-05:00", late_penalty="2%/hour", grace="15m")
    report = run_batch(
        BatchOptions(week=3, batch_dir=export, out=out, seed=3, jobs=1, quiet=True, intake=intake),
        grade_fn=FAKE,
    )
    assert report["layout"] == "gradescope"
    per = report["per_student"]
    assert set(per) == {"1001", "A-1", "a-1", "ann@uni.edu"}
    assert student_stem("A-1") != student_stem("a-1")  # collide after lower-casing: kept apart
    jane = json.loads((out / "1001.json").read_text())
    # resubmission: the later 9003 (00:30, 30 min late: past 15 min grace, 1 hour at 2 %) is graded
    assert jane["batch"]["identity"]["platform_id"] == "9003" and jane["late"]["penalty_points"] == 0.2
    assert jane["score"] == 8.8 and jane["late"]["seconds_late"] == 1800
    assert any("1001: resubmitted; graded submission 9003" in n for n in report["intake"]["notes"])
    group = [json.loads((out / f"{student_stem(s)}.json").read_text()) for s in ("A-1", "a-1")]
    assert [(g["score"], g["batch"]["identity"]["name"]) for g in group] == [
        (5.8, "John Smith"),
        (5.8, "Joan Smith"),
    ]
    assert group[0]["late"]["penalty_points"] == 0.2  # one hour late at 2 %/hour of 10
    ann = json.loads((out / f"{student_stem('ann@uni.edu')}.json").read_text())
    assert ann["status"] == "held" and "no distinct submission times" in ann["message"]
    assert any("submission_9999" in u for u in report["intake"]["unplaced"])


def test_hostile_entries_inside_exports(tmp_path: Path) -> None:
    outside = tmp_path / "secret.txt"
    outside.write_text("score 10\n")
    folder = tmp_path / "moodle"
    (folder / "Eve_601_assignsubmission_file").mkdir(parents=True)
    os.symlink(outside, folder / "Eve_601_assignsubmission_file" / "answer.txt")  # a link: never read
    (folder / "Bob_602_assignsubmission_file").mkdir()
    (folder / "Bob_602_assignsubmission_file" / "answer.txt").write_text("score 5\n")
    os.symlink(tmp_path, folder / "Mal_603_assignsubmission_file")  # a linked folder
    klass = read_class(folder, IntakeOptions())
    read = {s.id: read_submission(s, week=3) for s in klass.students}
    assert read["601"].refused and "link" in read["601"].refused and not read["601"].files
    assert read["602"].files == {"answer.txt": b"score 5\n"}
    assert read["603"].refused and "link" in read["603"].refused
    # a Canvas zip: a symlink entry, an id with control characters cannot arise (digits), a zip bomb
    # in a student's own nested zip is refused by that student's limits
    make_zip(
        tmp_path / "c.zip",
        {"bob_1_1_answer.txt": "score 5\n"},
        symlinks={"eve_2_2_answer.txt": "/etc/passwd"},
    )
    canvas = {
        s.id: read_submission(s, week=3) for s in read_class(tmp_path / "c.zip", IntakeOptions()).students
    }
    assert canvas["2"].refused and "link" in canvas["2"].refused and canvas["1"].files
    # Gradescope: SIDs are the export's text: control characters refuse that student only; YAML tags that
    # would build objects are refused with the file
    meta = (
        'submission_1:\n  :submitters:\n  - :sid: "evil\\e[2J"\n  :created_at: 2026-03-01 10:00:00 -05:00\n'
        "submission_2:\n  :submitters:\n  - :sid: '7'\n  :created_at: 2026-03-01 10:00:00 -05:00\n"
    )
    make_zip(
        tmp_path / "g.zip",
        {
            "submission_metadata.yml": meta,
            "submission_1/answer.txt": "x",
            "submission_2/answer.txt": "score 4\n",
        },
    )
    gs = {s.id: read_submission(s, week=3) for s in read_class(tmp_path / "g.zip", IntakeOptions()).students}
    assert gs["evil\x1b[2J"].refused and "control" in gs["evil\x1b[2J"].refused and gs["7"].files
    make_zip(
        tmp_path / "t.zip",
        {
            "submission_metadata.yml": "a: !!python/object/apply:os.system ['true']\n",
            "submission_1/answer.txt": "x",
        },
    )
    with pytest.raises(IntakeError, match="cannot be read as YAML"):
        read_class(tmp_path / "t.zip", IntakeOptions())
    with pytest.raises(IntakeError, match="not a Canvas, Moodle or Gradescope download"):
        read_class(make_zip(tmp_path / "x.zip", {"alice/answer.txt": "x"}), IntakeOptions())


def test_a_folder_and_a_zip_for_one_id_is_held_not_invalid(tmp_path: Path) -> None:
    klass = tmp_path / "class"
    (klass / "dave").mkdir(parents=True)
    (klass / "dave" / "answer.txt").write_text("score 5\n")
    make_zip(klass / "dave.zip", {"answer.txt": "score 6\n"})
    (klass / "erin").mkdir()
    (klass / "erin" / "answer.txt").write_text("score 7\n")
    stream = io.StringIO()
    report = run_batch(
        BatchOptions(week=3, batch_dir=klass, out=tmp_path / "out", seed=1, jobs=1),
        grade_fn=FAKE,
        stream=stream,
    )
    assert report["counts"] == {"graded": 1, "invalid": 0, "held": 1, "timeout": 0, "crashed": 0}
    assert "held (yours to sort out, not graded): dave: both a folder and a zip" in stream.getvalue()
    page = (tmp_path / "out" / "dave.html").read_text()
    assert "being sorted out" in page and "submit again" not in page
    assert "Held: yours to sort out, not graded (1)" in (tmp_path / "out" / "summary.html").read_text()


def test_real_grading_of_a_canvas_download(tmp_path: Path) -> None:
    """The real grader on Canvas's entries: the solution's files uploaded one by one (go_to_goal.py
    re-uploaded, so Canvas named it go_to_goal-1.py) are graded in full, then charged a day late; a
    student who uploaded only notes is invalid, not a zero-point grading."""
    solutions = Path(__file__).resolve().parents[2] / "solutions" / "week3"
    entries = {}
    for number, path in enumerate(sorted(solutions.glob("*.py")), start=1):
        shown_name = "go_to_goal-1.py" if path.name == "go_to_goal.py" else path.name
        entries[f"doejane_LATE_101_{9000 + number}_{shown_name}"] = path.read_text()
    entries["notes_102_9100_notes.txt"] = "my notes\n"
    export = make_zip(tmp_path / "CS101-HW3_submissions.zip", entries)
    (tmp_path / "times.csv").write_text("id,submitted_at\n101,2026-03-02T10:00:00-05:00\n")
    intake = IntakeOptions(times=tmp_path / "times.csv", deadline=DEADLINE, late_penalty="10%/day")
    report = run_batch(
        BatchOptions(
            week=3, batch_dir=export, out=tmp_path / "out", seed=5, jobs=1, quiet=True, intake=intake
        )
    )
    jane = json.loads((tmp_path / "out" / "101.json").read_text())
    assert jane["status"] == "graded" and jane["late"]["score_before"] == jane["max_score"]
    assert sum(c["points"] for c in jane["checks"]) == jane["max_score"]  # check points untouched
    assert jane["score"] == round(jane["max_score"] * 0.9, 6) and jane["late"]["note"] == "1 day late"
    assert "Late penalty" in (tmp_path / "out" / "101.html").read_text()
    notes = json.loads((tmp_path / "out" / "102.json").read_text())
    assert notes["status"] == "invalid" and "holds none of week 3's files" in notes["message"]
    assert report["counts"] == {"graded": 1, "invalid": 1, "timeout": 0, "crashed": 0}


def test_the_command_line_reads_the_intake_options() -> None:
    """docs/batch.md's Canvas line, parsed as `grade` parses it, gives the options the tests above use."""
    import shlex

    from grader.cli import _parser

    line = (
        "week3 --batch CS101-HW3_submissions.zip --roster gradebook.csv --deadline 2026-03-01T23:59-05:00 "
        "--late-penalty 10%/day --late-cap 50% --times times.csv --grace 15m --late-floor 20%"
    )
    options = BatchOptions.from_args(_parser().parse_args(shlex.split(line)))
    assert options.intake == IntakeOptions(
        roster=Path("gradebook.csv"),
        times=Path("times.csv"),
        deadline=DEADLINE,
        late_penalty="10%/day",
        late_cap="50%",
        late_floor="20%",
        grace="15m",
    )
    policy = options.intake.policy()
    assert policy is not None and (
        policy.percent,
        policy.interval_s,
        policy.cap_percent,
        policy.floor_percent,
        policy.grace_s,
    ) == (10.0, 86400, 50.0, 20.0, 900)


def test_file_times_only_when_asked_and_the_caps_of_an_export(tmp_path: Path) -> None:
    from grader.batch.export_files import ExportLimits, ExportRefused
    from grader.batch.zips import Limits

    path = tmp_path / "dl.zip"
    with zipfile.ZipFile(path, "w") as archive:
        info = zipfile.ZipInfo("doejane_101_1_answer.txt", date_time=(2026, 3, 2, 9, 30, 0))
        archive.writestr(info, "score 5\n" * 40)
    assert read_class(path, IntakeOptions()).students[0].identity.submitted_at == ""  # never unasked
    with pytest.raises(IntakeError, match="give --timezone"):
        read_class(path, IntakeOptions(file_times=True))
    asked = read_class(path, IntakeOptions(file_times=True, timezone="UTC")).students[0]
    assert asked.identity.submitted_at == "2026-03-02T09:30:00+00:00"
    # the whole export's cap, and each student's own limits on their entries
    with pytest.raises(ExportRefused, match="more than 100 bytes"):
        list_export(path, ExportLimits(max_total_bytes=100))
    refused = read_submission(asked, Limits(max_total_bytes=200), week=3)
    assert refused.refused and "size limit" in refused.refused and not refused.files


def test_a_roster_over_a_class_folder(tmp_path: Path) -> None:
    klass = tmp_path / "class"
    for sid in ("alice", "bob"):
        (klass / sid).mkdir(parents=True)
        (klass / sid / "answer.txt").write_text("score 5\n")
    (tmp_path / "roster.csv").write_text(
        "Name;Email;ID;Section\nAlice A;alice@x;alice;1\nCarl C;carl@x;carl;2\n"
    )
    read = read_class(klass, IntakeOptions(roster=tmp_path / "roster.csv"))
    assert read.layout == "folder" and read.missing == ["carl"] and read.not_on_roster == ["bob"]
    alice = next(s for s in read.students if s.id == "alice")
    assert (alice.identity.name, alice.identity.login, alice.identity.section) == ("Alice A", "alice@x", "1")
    (tmp_path / "twice.csv").write_text("id,name\nalice,A\nalice,B\n")
    with pytest.raises(IntakeError, match="lines 2 and 3"):
        read_class(klass, IntakeOptions(roster=tmp_path / "twice.csv"))
    (tmp_path / "noid.csv").write_text("fruit,colour\napple,red\n")
    with pytest.raises(IntakeError, match="no id column"):
        read_class(klass, IntakeOptions(roster=tmp_path / "noid.csv"))


def test_a_download_zipped_again_inside_one_folder(tmp_path: Path) -> None:
    entries = {f"CS101 submissions/{name}": text for name, text in moodle_entries(flat=True).items()}
    klass = read_class(make_zip(tmp_path / "again.zip", entries), IntakeOptions())
    assert klass.layout == "moodle" and [s.id for s in klass.students] == ["501", "502", "503"]
    jane = read_submission(klass.students[0], week=3)
    assert jane.files == {"answer.txt": b"score 10\n"}
