"""A batch's pages with the real grader (a week-3 class: the solution and a broken zip, hidden checks):

- one grader version string in every file of the batch (each student's JSON and report, the fallback page,
  gradebook.csv, summary.html, batch.json): the batch's grader fingerprint; the old grading function,
  which left each report with the grading's own version, is caught (tests/data/pages_wrong);
- a student's page is small (at most 150 KB) and loads nothing: each run's replay is a page of its own
  under replays/<stem>/, which loads the replay's script and styles from the batch's assets/ and plays
  in Chromium under its Content-Security-Policy; a replay page pointing elsewhere is caught;
- the replay page holds the rows the self-contained report embeds for that run (the same run plays), and
  a page whose plots would exceed the budget is drawn with fewer points until it fits;
- a regrade leaves only its own replay pages, and a link planted at a student's replay folder is refused
  (a clear that follows it, tests/data/pages_wrong/clear_by_path.py, is caught).
"""

from __future__ import annotations

import base64
import csv
import html
import importlib.util
import json
import re
import shutil
import sys
import zlib
from pathlib import Path

import pytest

from grader.batch.cache import grader_fingerprint
from grader.batch.runner import BatchOptions, run_batch
from grader.report.html import PAGE_BYTES, render_report, render_report_pages

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))
from browser import chromium_context, load_synthetic  # noqa: E402

WRONG = ROOT / "tests" / "data" / "pages_wrong"


def small_class(folder: Path, broken: bool = True) -> Path:
    shutil.copytree(ROOT / "solutions" / "week3", folder / "sol")
    if broken:
        (folder / "broken.zip").write_bytes(b"PK\x03\x04 not a zip")
    return folder


@pytest.fixture(scope="module")
def batch(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("pages")
    klass = small_class(root / "class")
    report = run_batch(BatchOptions(week=3, batch_dir=klass, out=root / "out", seed=77, jobs=1, quiet=True,
                                    hidden=True))
    assert report["counts"]["graded"] == 1 and report["counts"]["invalid"] == 1, report["counts"]
    return root / "out"


def versions(out: Path) -> dict[str, set[str]]:
    """Every grader version each file of the batch states, by file."""
    found: dict[str, set[str]] = {}
    for path in out.glob("*.json"):
        value = json.loads(path.read_text())
        found[path.name] = ({value["grader"]} if path.name == "batch.json" else
                            {value["grader_version"], value["batch"]["grader"]})
    for path in out.glob("*.html"):
        text = html.unescape(path.read_text())
        found[path.name] = set(re.findall(r"grader (?:<code>)?([0-9][^ <;]*?)(?:</code>|;)", text))
    with (out / "gradebook.csv").open() as stream:
        found["gradebook.csv"] = {row["grader"] for row in csv.DictReader(stream)}
    return found


def test_every_file_of_a_batch_states_one_grader_version(batch) -> None:
    found = versions(batch)
    assert {"sol.json", "sol.html", "broken.json", "broken.html", "summary.html", "batch.json",
            "gradebook.csv"} <= set(found)
    assert all(found.values()), found                    # each file states one
    assert set().union(*found.values()) == {grader_fingerprint()}, found


def test_the_version_check_catches_reports_with_their_own_version(tmp_path, monkeypatch) -> None:
    monkeypatch.syspath_prepend(str(WRONG))          # the grading processes import it from sys.path
    klass = small_class(tmp_path / "class", broken=False)
    run_batch(BatchOptions(week=3, batch_dir=klass, out=tmp_path / "out", seed=77, jobs=1, quiet=True),
              grade_fn="own_version_task:grade")
    found = versions(tmp_path / "out")
    assert len(set().union(*found.values())) == 2, found
    assert found["sol.html"] != {grader_fingerprint()}, found


def test_a_student_page_is_small_and_its_replays_are_pages_of_their_own(batch) -> None:
    page = (batch / "sol.html").read_text()
    assert len(page.encode()) <= PAGE_BYTES
    assert "<iframe" not in page and "<script" not in page
    links = re.findall(r'class="replay-link" href="([^"]+)"', page)
    assert len(links) >= 3 and all(link.startswith("replays/sol/") for link in links)
    for link in links:
        replay = (batch / link).read_text()
        assert '<script src="../../assets/replay.js"></script>' in replay and len(replay) < 100_000
    assert {p.name for p in (batch / "assets").iterdir()} == {"replay.js", "replay.css"}


@pytest.fixture(scope="module")
def chromium():
    yield from chromium_context({"width": 1100, "height": 800})


def play(chromium, path: Path, ready_ms: int = 20_000) -> dict:
    """Open a replay page, play it for a moment; what it shows and any console error."""
    page = chromium.new_page()
    errors: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(path.resolve().as_uri())
    page.wait_for_load_state("load")
    try:
        page.locator("body[data-ready='1']").wait_for(state="attached", timeout=ready_ms)
    except Exception as exc:  # noqa: BLE001 - a page that never starts: reported below, with the errors
        errors.append(f"never ready: {type(exc).__name__}")
        page.close()
        return {"errors": errors}
    page.evaluate("() => window.simiam.play()")
    page.wait_for_function("() => window.simiam.state().t > 0.2", timeout=10_000)
    state = page.evaluate("() => window.simiam.state()")
    page.close()
    return {"errors": errors, "state": state}


@pytest.mark.browser
def test_a_replay_page_plays_with_the_shared_assets(batch, chromium, tmp_path) -> None:
    page = sorted((batch / "replays" / "sol").glob("*.html"))[0]
    shown = play(chromium, page)
    assert shown["errors"] == [] and shown["state"]["rows"] > 100, shown
    # the same page pointing one folder short of the assets never starts
    wrong = batch / "replays" / "sol" / "wrong-depth.html"
    wrong.write_text(page.read_text().replace("../../assets/", "../assets/"))
    try:
        # (its script is refused at once: the console says so before the short wait ends)
        assert play(chromium, wrong, ready_ms=1_500)["errors"], "a replay page without its script"
    finally:
        wrong.unlink()


def test_a_replay_page_holds_the_rows_the_self_contained_report_embeds() -> None:
    synthetic = load_synthetic("synthetic_pages")
    traces = {"week3.go_to_goal.reach_goals": synthetic.make_trace(week=3, seconds=40.0),
              "week3.go_to_goal.reach_goals#2": synthetic.make_trace(week=3, seconds=20.0)}
    result = {"week": 3, "status": "graded", "score": 1.0, "max_score": 1.0, "checks": [
        {"id": "week3.go_to_goal.reach_goals", "name": "reach", "kind": "scenario", "status": "failed",
         "points": 0.0, "max_points": 1.0, "details": {"traces": list(traces)}, "plots": ["trajectory"]}]}
    inline = html.unescape(render_report(result, traces))
    embedded = [json.loads(d) for d in re.findall(r'id="simiam-data">(.*?)</script>', inline, re.S)]
    page, replays = render_report_pages(result, traces, folder="replays/s", assets="../../assets")
    own = [json.loads(zlib.decompress(base64.b64decode(re.search(
               r'<script type="application/x-simiam-deflate" id="simiam-data">(.*?)</script>',
               replays[name], re.S)[1]))) for name in sorted(replays)]
    assert len(embedded) == len(own) == 2 and embedded == own
    linked = sorted(re.findall(r'href="(replays/s/[^"]+)"', page))
    assert linked == [f"replays/s/{name}" for name in sorted(replays)]


def test_a_page_over_its_budget_is_drawn_with_fewer_points(monkeypatch) -> None:
    import grader.report.html as report_html

    synthetic = load_synthetic("synthetic_budget")
    traces = {f"week3.go_to_goal.reach_goals#{k}" if k > 1 else "week3.go_to_goal.reach_goals":
              synthetic.make_trace(week=3, seconds=8.0 + k) for k in range(1, 4)}
    result = {"week": 3, "status": "graded", "score": 0.0, "max_score": 1.0, "checks": [
        {"id": "week3.go_to_goal.reach_goals", "name": "reach", "kind": "scenario", "status": "failed",
         "points": 0.0, "max_points": 1.0, "details": {"traces": list(traces)},
         "plots": ["trajectory", "heading"]}]}
    roomy, replays = render_report_pages(result, traces, folder="r", assets="a")
    monkeypatch.setattr(report_html, "PAGE_BYTES", len(roomy.encode()) - 1)
    tight, same = render_report_pages(result, traces, folder="r", assets="a")
    assert len(tight.encode()) < len(roomy.encode()) and same == replays
    assert tight.count("<svg") == roomy.count("<svg") and tight.count("replay-link") == 3


def test_a_regrade_leaves_only_its_own_replay_pages_and_writes_through_no_link(tmp_path) -> None:
    from grader.batch.pages import replay_pages, write_student_pages
    from simiam.safe_write import LinkRefused

    out = tmp_path / "out"
    write_student_pages(out, "ann", "<p>first</p>", {"a.html": "A", "b.html": "B"})
    write_student_pages(out, "ann", "<p>second</p>", {"a.html": "A2"})
    assert sorted(p.name for p in (out / "replays" / "ann").iterdir()) == ["a.html"]
    assert (out / "ann.html").read_text() == "<p>second</p>"
    # only plain names from an outcome: nothing hidden, no folder, no parent
    pages = replay_pages({"replays": {"../x.html": "X", ".h.html": "H", "d/e.html": "E", "ok.html": "OK",
                                      "n.html": 3}})
    assert pages == {"ok.html": "OK"}
    # a link planted where a student's replay folder goes: refused, and what it points to is untouched
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "keep.html").write_text("keep")
    (out / "replays" / "bob").symlink_to(elsewhere)
    with pytest.raises(LinkRefused):
        write_student_pages(out, "bob", "<p>bob</p>", {"a.html": "A"})
    assert [p.name for p in elsewhere.iterdir()] == ["keep.html"]
    spec = importlib.util.spec_from_file_location("clear_by_path", WRONG / "clear_by_path.py")
    wrong = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(wrong)
    wrong.clear(out, "bob")                          # the check above catches a clear that follows it
    assert [p.name for p in elsewhere.iterdir()] == []
