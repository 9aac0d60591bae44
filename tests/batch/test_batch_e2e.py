"""The real grader behind the batch: a small week-3 class (solution, stub, a syntax error, a zipped
solution in a nested folder, a broken zip) gets the right statuses and scores, and --jobs 1 and --jobs 2
give identical per-student results."""

from __future__ import annotations

import csv
import json
import re
import shutil
import zipfile
from pathlib import Path

import pytest

from grader.batch.runner import BatchOptions, run_batch

ROOT = Path(__file__).resolve().parents[2]
pytest.importorskip("grader.grading")


def week3_class(folder: Path) -> Path:
    shutil.copytree(ROOT / "solutions" / "week3", folder / "sol")
    shutil.copytree(ROOT / "assignments" / "week3", folder / "stub")
    shutil.copytree(ROOT / "solutions" / "week3", folder / "syntax")
    broken = folder / "syntax" / "go_to_goal.py"
    lines = broken.read_text().splitlines(True)
    start = next(i for i, line in enumerate(lines) if "START CODE BLOCK" in line)
    lines.insert(start + 1, "        theta_g = (\n")
    broken.write_text("".join(lines))
    with zipfile.ZipFile(folder / "zipped.zip", "w") as archive:
        for path in sorted((ROOT / "solutions" / "week3").glob("*.py")):
            archive.write(path, f"week3/{path.name}")
    (folder / "broken.zip").write_bytes(b"PK\x03\x04 this is not a zip")
    return folder


def per_student(out: Path) -> dict[str, dict]:
    found = {}
    for path in out.glob("*.json"):
        if path.name != "batch.json":
            result = json.loads(path.read_text())
            result.pop("timing")
            result.pop("time_budget", None)   # what the worker's clock measured: how it ran, not what
            found[path.stem] = result
    return found


def test_week3_class_with_the_real_grader(tmp_path: Path) -> None:
    klass = week3_class(tmp_path / "class")
    base = {"week": 3, "batch_dir": klass, "seed": 2014, "quiet": True, "budget_s": 240.0}
    report = run_batch(BatchOptions(**base, out=tmp_path / "two", jobs=2))
    if report["counts"]["crashed"]:
        pytest.fail(json.dumps({p.stem: json.loads(p.read_text()).get("message") for p in
                                (tmp_path / "two").glob("*.json")}))
    assert report["counts"] == {"graded": 4, "invalid": 1, "timeout": 0, "crashed": 0}
    rows = {r["student"]: r for r in csv.DictReader((tmp_path / "two" / "gradebook.csv").open())}
    assert rows["sol"]["total"] == rows["sol"]["max"] == rows["zipped"]["total"]
    assert float(rows["stub"]["total"]) == 0.0
    assert 0 < float(rows["syntax"]["total"]) < float(rows["sol"]["total"])
    syntax = json.loads((tmp_path / "two" / "syntax.json").read_text())
    assert "go_to_goal.py" in json.dumps(syntax["problems"]) and "simiam-batch-" not in json.dumps(syntax)
    assert json.loads((tmp_path / "two" / "zipped.json").read_text())["batch"]["root"] == "week3"
    assert "not a readable zip" in rows["broken"]["message"]
    assert (tmp_path / "two" / "sol.html").stat().st_size > 1000
    # the summary links each scenario run's replay, and every link lands on a replay in the report
    summary = (tmp_path / "two" / "summary.html").read_text()
    links = re.findall(r'href="(sol\.html)#(run-[^"]+)"', summary)
    assert len(links) >= 3
    report_html = (tmp_path / "two" / "sol.html").read_text()
    for _, anchor in links:
        assert report_html.count(f'id="{anchor}"') == 1
        run = report_html.split(f'id="{anchor}"', 1)[1].split('<div class="run"', 1)[0]
        replay = re.search(r'class="replay-link" href="([^"]+)"', run.split("</article>", 1)[0])
        assert replay and replay[1].startswith("replays/sol/"), run[:300]  # its own page (batch/pages.py)
        assert 'src="../../assets/replay.js"' in (tmp_path / "two" / replay[1]).read_text()
    again = run_batch(BatchOptions(**base, out=tmp_path / "two", jobs=2))
    assert again["this_run"] == {"graded_now": 0, "skipped": 5}
    one_report = run_batch(BatchOptions(**base, out=tmp_path / "one", jobs=1))
    if one_report["grader"] != report["grader"]:
        pytest.skip("the grader's files changed between the two runs (a live checkout)")
    assert per_student(tmp_path / "one") == per_student(tmp_path / "two")


def test_a_grading_machine_with_another_grader_refuses(tmp_path: Path) -> None:
    from grader.batch.task import GraderMismatch, grade_task

    task = {"student": "a", "week": 3, "seed": 1, "hidden": False, "files": {}, "grader": "0.0.0+other",
            "check_grader": True}
    with pytest.raises(GraderMismatch, match="install the same version everywhere"):
        grade_task(task)


def test_the_grade_command_line_runs_a_batch(tmp_path: Path) -> None:
    from grader.cli import main

    klass = tmp_path / "class"
    shutil.copytree(ROOT / "assignments" / "week2", klass / "stub")
    (klass / "broken.zip").write_bytes(b"not a zip")
    code = main(["week2", "--batch", str(klass), "--out", str(tmp_path / "out"), "--quiet", "--jobs", "1",
                 "--seed", "7"])
    assert code == 1                        # ran, but one submission is invalid
    batch = json.loads((tmp_path / "out" / "batch.json").read_text())
    assert batch["week"] == 2 and batch["seed"] == 7 and batch["counts"]["invalid"] == 1
    assert json.loads((tmp_path / "out" / "stub.json").read_text())["status"] == "graded"
    assert main(["week2", "--batch", str(tmp_path / "nowhere"), "--out", str(tmp_path / "o2")]) == 2
