"""Class files: the gradebook (one column per check, formulas defused), the Gradescope export, the summary
page (pass rates, histogram, links, escaping) and the progress line."""

from __future__ import annotations

import csv
import io
import json

import batch_fake_grader

from grader.batch import summary
from grader.batch.exports import gradebook_csv, gradescope_result, safe_cell
from grader.batch.progress import Progress, format_duration
from grader.batch.summary import check_stats, graded_scores, replay_links, shortened, summary_html

TASK = {"week": 3, "seed": 1, "student": "x"}


def klass() -> dict[str, dict]:
    results = {sid: batch_fake_grader.result_for({**TASK, "student": sid}, score)
               for sid, score in (("alice", 10.0), ("bob", 4.0), ("carl", 0.0))}
    results["dan"] = {"week": 3, "score": 0.0, "max_score": None, "status": "timeout", "checks": [],
                      "message": "grading took longer than 300 s\nand was stopped"}
    results["eve"] = {"week": 3, "score": 0.0, "max_score": None, "status": "invalid", "checks": [],
                      "message": "=cmd|' /C calc'!A0"}
    return results


def test_gradebook_has_one_column_per_check_and_defuses_formulas(wrong) -> None:
    rows = list(csv.DictReader(io.StringIO(gradebook_csv(klass()))))
    assert list(rows[0]) == ["student", "week3.fake.a", "week3.fake.b", "week3.fake.c", "total", "max",
                             "status", "message", "late_penalty", "score_before_penalty", "grader"]
    by_id = {r["student"]: r for r in rows}
    assert by_id["bob"]["week3.fake.a"] == "4.0" and by_id["bob"]["week3.fake.b"] == "0.0"
    assert by_id["dan"]["max"] == "10.0" and by_id["dan"]["week3.fake.a"] == ""
    assert by_id["dan"]["message"] == "grading took longer than 300 s and was stopped"
    assert by_id["eve"]["message"].startswith("'=")
    assert wrong.csv_cell_as_is("=cmd") != safe_cell("=cmd")   # the check above would catch a pass-through
    assert safe_cell(-1.5) == -1.5


def test_gradescope_export() -> None:
    export = gradescope_result(klass()["bob"])
    assert export["score"] == 4.0
    assert [t["status"] for t in export["tests"]] == ["passed", "failed", "passed"]
    assert [t["visibility"] for t in export["tests"]] == ["visible", "visible", "hidden"]
    assert export["tests"][0] == {"name": "week3.fake.a: first", "score": 4.0, "max_score": 4.0,
                                  "status": "passed", "output": "", "visibility": "visible"}
    timeout = gradescope_result(klass()["dan"])
    assert timeout["score"] == 0.0 and timeout["tests"] == [] and timeout["output"].startswith("timeout:")
    json.dumps(export, allow_nan=False)


def test_summary_statistics_histogram_and_escaping() -> None:
    results = klass()
    stats = {s["id"]: s for s in check_stats(results)}
    assert stats["week3.fake.a"]["pass_rate"] == 2 / 3 and stats["week3.fake.b"]["mean_points"] == 2.0
    assert sorted(graded_scores(results)) == [0.0, 4.0, 10.0]     # timeouts and invalids are left out
    results["<script>"] = {**results["bob"], "message": "<b>bold</b>"}
    results["ann #2"] = {**results["bob"]}
    page = summary_html(results, {sid: sid for sid in results}, {"week": 3, "seed": 1, "grader": "g"})
    assert "<script>" not in page and "&lt;script&gt;" in page and "&lt;b&gt;" in page
    assert 'href="alice.html"' in page and 'class="plot histogram"' in page
    assert ": 3</title></rect>" in page and ": 1</title></rect>" in page   # bob 3 times, alice, carl once
    assert 'href="ann%20%232.html"' in page
    assert "80%" in page          # fake.a: alice, bob and the two copies of bob pass; carl fails


def test_summary_links_each_run_replay_once_and_marks_failed_runs() -> None:
    results = klass()
    runs = ["week3.go_to_goal.reach_goals", "week3.go_to_goal.reach_goals#2"]
    results["bob"]["checks"][1]["details"]["traces"] = runs
    results["bob"]["checks"].append({"id": "week3.pid.settle_time", "status": "passed", "points": 1.0,
                                     "max_points": 1.0, "details": {"traces": runs[1:]}})
    [group] = replay_links(results["bob"], "b%20b.html")
    assert group["name"] == "go_to_goal.reach_goals" and [(r["href"], r["text"]) for r in group["runs"]] == [
        ("b%20b.html#run-week3.go_to_goal.reach_goals", "1"),
        ("b%20b.html#run-week3.go_to_goal.reach_goals_2", "2")]
    assert group["runs"][1]["title"] == "week3.fake.b: failed; week3.pid.settle_time: passed"
    assert [r["failed"] for r in group["runs"]] == [True, True]   # red if any check on the run failed
    results["bob"]["checks"][1]["status"] = "passed"
    [group] = replay_links(results["bob"], "b.html")
    assert [r["failed"] for r in group["runs"]] == [False, False]
    page = summary_html(results, {sid: sid for sid in results}, {"week": 3, "seed": 1, "grader": "g"})
    assert 'href="bob.html#run-week3.go_to_goal.reach_goals_2"' in page and "<th>replays</th>" in page
    assert replay_links(results["alice"], "alice.html") == []      # no scenario run kept: no link


def test_summary_tells_blending_from_switching_and_colours_each_run_by_its_own_record() -> None:
    """The summary labelled week 5's replays "reach_goal 1 2 1 2" (blending and switching runs could not
    be told apart) and drew a run that reached its goal red because the other run of its check missed."""
    def check(part: str, reached: list[bool]) -> dict:
        cid = f"week5.{part}.reach_goal"
        keys = [cid] + [f"{cid}#{k + 1}" for k in range(1, len(reached))]
        return {"id": cid, "status": "passed" if all(reached) else "failed", "points": 0.0, "max_points": 1.0,
                "details": {"traces": keys, "runs": [{"reached": r, "collided": False, "problem": ""}
                                                     for r in reached]}}

    result = {"checks": [check("blending", [True, True]), check("switching", [True, False])]}
    groups = replay_links(result, "s.html")
    assert [g["name"] for g in groups] == ["blending.reach_goal", "switching.reach_goal"]
    assert [[r["failed"] for r in g["runs"]] for g in groups] == [[False, False], [False, True]]
    assert groups[1]["runs"][0]["title"] == "week5.switching.reach_goal: failed"  # the check's verdict stays


def test_summary_cuts_a_long_message_at_a_word_and_says_so() -> None:
    """The summary cut messages at 300 characters mid-word, without a mark."""
    message = "your supervisor raised an error " * 20
    cut = shortened(message.strip(), 300)
    assert cut.endswith("…") and len(cut) <= 300
    assert message.startswith(cut[:-1] + " ")  # whole words, then the mark
    assert shortened("short enough", 300) == "short enough"
    results = {"zed": {"week": 3, "status": "crashed", "score": 0.0, "checks": [], "message": message}}
    page = summary_html(results, {"zed": "zed"}, {"week": 3, "seed": 1, "grader": "g"})
    # the cell shows the message's start, cut at a word; the whole text is one click away (details)
    start = shortened(message.strip(), summary.MESSAGE_SHOWN)
    assert start.endswith("…") and f"<summary>{start}</summary>{message.strip()}</details></td>" in page
    short = {"zed": {**results["zed"], "message": "your supervisor raised an error"}}
    assert "<details" not in summary_html(short, {"zed": "zed"}, {"week": 3})


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_progress_line_counts_rate_eta_and_modes() -> None:
    clock, stream = Clock(), io.StringIO()
    bar = Progress(10, stream=stream, tty=False, period_s=10, clock=clock)
    clock.now = 30.0
    bar.done("graded")
    bar.done("skipped")
    assert "[2/10]" in bar.line() and "graded 1" in bar.line() and "skipped 1" in bar.line()
    assert "2.0/min" in bar.line() and "ETA 4m00s" in bar.line()
    assert len(stream.getvalue().splitlines()) == 1         # periodic, not one line per student
    clock.now = 41.0
    bar.done("timeout")
    assert len(stream.getvalue().splitlines()) == 2
    last = Progress(1, stream=io.StringIO(), tty=False, period_s=10, clock=clock)
    clock.now = 60.0
    last.done("graded")
    last.close()
    assert last.stream.getvalue().count("[1/1]") == 1       # the end is shown once, not twice
    tty = io.StringIO()
    live = Progress(3, stream=tty, tty=True, clock=clock)
    live.done("crashed")
    live.close()
    assert tty.getvalue().startswith("\r") and tty.getvalue().count("\n") == 1
    quiet = io.StringIO()
    Progress(3, stream=quiet, quiet=True).done("graded")
    assert quiet.getvalue() == ""
    assert format_duration(3725) == "1h02m" and format_duration(59) == "59s"


def test_every_gradescope_file_is_written_and_a_failed_write_is_raised(tmp_path, monkeypatch) -> None:
    """The Gradescope files are written by several threads: all of them, and an error is not lost there
    (the runner then says the batch stopped and that a rerun resumes)."""
    import pytest

    from grader.batch import exports

    results = klass()
    stems = {sid: sid for sid in results}
    exports.write_exports(tmp_path, results, stems)
    for sid in results:
        assert json.loads((tmp_path / "gradescope" / sid / "results.json").read_text()) == \
            json.loads(json.dumps(gradescope_result(results[sid])))
    real = exports.write_json

    def disk_full_for_carl(path, value, mode=None):
        if path.parent.name == "carl":
            raise OSError(28, "No space left on device")
        real(path, value, mode)
    monkeypatch.setattr(exports, "write_json", disk_full_for_carl)
    with pytest.raises(OSError, match="No space left"):
        exports.write_exports(tmp_path / "again", results, stems)
