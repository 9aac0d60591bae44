"""The report of every week at 1024 and 1280 px in headless Chromium, measured as a person sees it: no
text of a plot runs outside its picture (the state chart's "bstacle_cleared", the week-6 legend cut at the
right), no two texts of a plot cover each other, and the page needs no sideways scrolling.

Each week's report holds its real checks (ids, names, declared plots) with one short run of the course's
solution per scenario check: the plots of every week, at a cost of a few seconds."""

from __future__ import annotations

import pytest
from browser import chromium_context, solution_trace

from grader.checks import checks_for_week
from grader.report import write_report

pytestmark = pytest.mark.browser
WIDTHS = (1024, 1280)
SECONDS = 12.0  # long enough for every week's states to switch, short enough to stay cheap

# every text box of every plot, and each pair of a plot's texts whose boxes overlap (by more than a pixel
# each way: a glyph's box may touch its neighbour's)
MEASURE = """() => {
  const out = {outside: [], overlaps: [], plots: 0,
               scroll: [document.documentElement.scrollWidth, innerWidth]};
  document.querySelectorAll('svg.plot').forEach((svg, k) => {
    const box = svg.getBoundingClientRect();
    if (box.width === 0) { return; }
    out.plots++;
    const texts = [...svg.querySelectorAll('text')].map(t => [t.textContent, t.getBoundingClientRect()])
      .filter(([s, r]) => s.trim() && r.width > 0);
    for (const [s, r] of texts) {
      if (r.left < box.left - 1 || r.right > box.right + 1 ||
          r.top < box.top - 1 || r.bottom > box.bottom + 1) {
        out.outside.push([k, s]);
      }
    }
    for (let i = 0; i < texts.length; i++) {
      for (let j = i + 1; j < texts.length; j++) {
        const [a, ra] = texts[i], [b, rb] = texts[j];
        const w = Math.min(ra.right, rb.right) - Math.max(ra.left, rb.left);
        const h = Math.min(ra.bottom, rb.bottom) - Math.max(ra.top, rb.top);
        if (w > 1 && h > 1) { out.overlaps.push([k, a, b]); }
      }
    }
  });
  return out;
}"""


def _week_result(week: int) -> tuple[dict, dict]:
    """A graded result of `week` with every visible check passed, and a solution run per scenario check."""
    checks, traces, trace = [], {}, None
    for check in checks_for_week(week):
        if check.visibility != "visible":
            continue
        checks.append({"id": check.id, "name": check.name, "kind": check.kind, "visibility": "visible",
                       "points": check.weight, "max_points": check.weight, "status": "passed",
                       "message": "", "details": {}, "plots": list(check.plots) if check.kind == "scenario"
                       else []})
        if check.kind == "scenario":
            trace = trace or solution_trace(week, SECONDS)
            traces[check.id] = trace
    total = sum(c["points"] for c in checks)
    result = {"week": week, "score": total, "max_score": total,
              "status": "graded", "seed": 1, "grader_version": "0.1.0", "check_set_hash": "0" * 16,
              "submission": f"week{week}", "isolation": "bwrap", "hidden": False, "checks": checks}
    return result, traces


@pytest.fixture(scope="module")
def reports(tmp_path_factory) -> dict[int, str]:
    out = tmp_path_factory.mktemp("reports")
    return {week: write_report(*_week_result(week), out / f"week{week}.html", replays="files").as_uri()
            for week in range(1, 8)}


@pytest.mark.parametrize("width", WIDTHS)
def test_every_weeks_report_reads_whole(reports: dict[int, str], width: int, tmp_path) -> None:
    seen = {}
    for context in chromium_context({"width": width, "height": 900}):
        page = context.new_page()
        for week, uri in reports.items():
            page.goto(uri)
            page.evaluate("document.querySelectorAll('details.check-body').forEach(d => d.open = true)")
            seen[week] = page.evaluate(MEASURE)
            page.screenshot(path=str(tmp_path / f"report-week{week}-{width}.png"), full_page=True)
    plotted = {week: m["plots"] for week, m in seen.items()}
    assert all(plotted[week] > 0 for week in (2, 3, 5, 6, 7)), plotted  # the weeks with runs drew them
    assert {week: m["outside"] for week, m in seen.items() if m["outside"]} == {}
    assert {week: m["overlaps"] for week, m in seen.items() if m["overlaps"]} == {}
    assert {week: m["scroll"] for week, m in seen.items() if m["scroll"][0] > m["scroll"][1]} == {}
