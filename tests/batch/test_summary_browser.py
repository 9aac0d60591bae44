"""summary.html in headless Chromium at 1024 and 1280 px: a class of 40 (and one of 400) with week 5's real
checks, replays on every scenario run, long ids and long messages, fits the window: no element's box lies
outside it, no text is clipped (a box whose content is wider than itself), no sideways scrolling, and a
student's row stays a few lines high. The template the summary had before (tests/data/summary_wrong) is
caught: its replays column pushed the messages out of the window."""

from __future__ import annotations

import importlib.util
import random
import sys
from pathlib import Path

import pytest
from jinja2 import Environment

from grader.batch.summary import summary_context, summary_html
from grader.checks import checks_for_week
from grader.report.html import page_text

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from browser import chromium_context  # noqa: E402

pytestmark = pytest.mark.browser
WRONG = Path(__file__).resolve().parents[1] / "data" / "summary_wrong" / "before_1024.py"
WIDTHS = (1024, 1280)
MESSAGES = (
    "",
    "go_to_goal.py line 57: ZeroDivisionError: float division by zero",
    "the robot reached the goal in 2 of 3 runs; in the third it stopped 0.41 m away after 60 s "
    "(heading error 1.2 rad). Check how theta_g is computed and that e_k is wrapped with atan2. " * 3,
    "could not import /tmp/simiam-batch-x8f/submission/assignments/week5/"
    "supervisors_and_controllers/a_very_long_path_without_a_single_space_in_it_at_all_qb_supervisor.py",
    "grading took longer than 300 s and was stopped",
)

# The element boxes that lie outside the window, the elements whose content is wider than their box, the
# page's scroll width and the tallest student row.
MEASURE = """() => {
  const width = document.documentElement.clientWidth;
  const out = {outside: [], clipped: [], scroll: document.documentElement.scrollWidth, width: width,
               tallest: 0};
  const name = e => e.tagName.toLowerCase() + (e.getAttribute('class') ? '.' + e.getAttribute('class') : '')
                    + ' "' + (e.textContent || '').trim().slice(0, 40) + '"';
  for (const e of document.body.querySelectorAll('*')) {
    const r = e.getBoundingClientRect();
    if (r.width === 0 && r.height === 0) { continue; }   // not shown (a closed details, an svg title)
    if (r.left < -0.5 || r.right > width + 0.5) {
      out.outside.push(name(e) + ' ' + Math.round(r.left) + '..' + Math.round(r.right));
    }
    if (e.clientWidth > 0 && e.scrollWidth > e.clientWidth) {
      out.clipped.push(name(e) + ' ' + e.scrollWidth + ' > ' + e.clientWidth);
    }
  }
  const tables = document.querySelectorAll('table');   // the students' table is the last one
  for (const row of tables[tables.length - 1].querySelectorAll('tr')) {
    out.tallest = Math.max(out.tallest, row.getBoundingClientRect().height);
  }
  return out;
}"""


def week5_class(n: int, seed: int = 5) -> tuple[dict[str, dict], dict[str, str]]:
    """`n` students graded on week 5's real checks (hidden ones included), every scenario check with one to
    three kept runs, some failed; a few ids and messages as long as they come."""
    rng = random.Random(seed)
    checks = checks_for_week(5)
    results, stems = {}, {}
    for k in range(n):
        sid = (f"student{k:03d}" if k % 9 else
               f"a-very-long-student-id-without-spaces-{k:03d}-" + "x" * 60)
        status = "graded" if k % 13 else rng.choice(["invalid", "timeout", "crashed"])
        result = {"week": 5, "status": status, "score": 0.0, "max_score": 0.0, "checks": [],
                  "message": MESSAGES[k % len(MESSAGES)] if status != "graded" or k % 4 == 0 else ""}
        for check in checks if status == "graded" else []:
            passed = rng.random() < 0.7
            record = {"id": check.id, "name": check.name, "kind": check.kind, "status":
                      "passed" if passed else "failed", "points": check.weight if passed else 0.0,
                      "max_points": check.weight, "message": "" if passed else MESSAGES[2][:200],
                      "details": {}}
            if check.kind == "scenario":
                runs = rng.randint(1, 3)
                keys = [check.id] + [f"{check.id}#{j}" for j in range(2, runs + 1)]
                record["details"] = {"traces": keys, "runs": [{"reached": passed or rng.random() < 0.5,
                                                               "collided": False} for _ in keys]}
            result["checks"].append(record)
            result["score"] += record["points"]
            result["max_score"] += check.weight
        results[sid] = result
        stems[sid] = sid[:70]
    return results, stems


META = {"week": 5, "seed": 1234567, "hidden": True, "grader": "0.1.0+eb240b366103", "incomplete": 0}


def measure(context, html: str, tmp_path: Path, width: int, opened: bool = False) -> dict:
    """MEASURE at `width`; `opened`: with every cut message opened to its whole text."""
    path = tmp_path / f"summary-{width}.html"
    path.write_text(html, encoding="utf-8")
    page = context.new_page()
    page.set_viewport_size({"width": width, "height": 900})
    page.goto(path.as_uri())
    page.wait_for_load_state("load")
    if opened:
        assert page.evaluate("() => document.querySelectorAll('details').length") > 0
        page.evaluate("() => document.querySelectorAll('details').forEach(d => d.open = true)")
    found = page.evaluate(MEASURE)
    page.close()
    return found


@pytest.fixture(scope="module")
def context():
    yield from chromium_context({"width": 1024, "height": 900})


@pytest.mark.parametrize("students", [40, 400])
def test_the_summary_fits_1024_and_1280_px_windows(context, tmp_path, students) -> None:
    results, stems = week5_class(students)
    html = summary_html(results, stems, META)
    assert html.count('class="run') > 10 * students         # every scenario run has its badge
    for width in WIDTHS:
        found = measure(context, html, tmp_path, width)
        assert found["outside"] == [], (width, found["outside"][:10])
        assert found["clipped"] == [], (width, found["clipped"][:10])
        assert found["scroll"] <= found["width"], (width, found["scroll"])
        # a row of a student who failed many runs (and has a long message) stays a few lines high
        assert found["tallest"] < 120, (width, found["tallest"])
        whole = measure(context, html, tmp_path, width, opened=True)     # the whole messages wrap too
        assert (whole["outside"], whole["clipped"]) == ([], []), (width, whole)


def test_the_check_catches_the_summary_before_it_fit(context, tmp_path) -> None:
    spec = importlib.util.spec_from_file_location("before_1024", WRONG)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    results, stems = week5_class(40)
    html = Environment(autoescape=True, finalize=page_text).from_string(module._TEMPLATE).render(
        **summary_context(results, stems, META))
    found = measure(context, html, tmp_path, 1024)
    assert found["outside"] and found["scroll"] > found["width"], found
