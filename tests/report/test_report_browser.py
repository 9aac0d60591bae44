"""The grader's report in headless Chromium: loads cleanly, plots render, student text stays text."""

from __future__ import annotations

import pytest

from grader.report import write_report

pytestmark = pytest.mark.browser


def test_report_in_the_browser(browser_context, week3_result, tmp_path):
    result, traces = week3_result
    path = write_report(result, traces, tmp_path / "week3.html")
    page = browser_context.new_page()
    errors: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(path.resolve().as_uri())
    page.wait_for_load_state("load")

    assert page.locator("table.checks tbody tr").count() == 4
    assert page.locator("table.checks tbody tr.failed").count() == 2
    boxes = [page.locator("svg.plot").nth(k).bounding_box() for k in range(page.locator("svg.plot").count())]
    assert len(boxes) == 4 and all(b and b["width"] > 200 and b["height"] > 150 for b in boxes)
    assert page.evaluate("window.pwned") is None
    assert page.locator("img[src=x]").count() == 0
    assert "<script>window.pwned = 1</script>" in page.inner_text("article#check-week3\\.ensure_w\\.keeps_w")

    page.locator("details.replay summary").first.click()  # the embedded replay runs, in its own sandbox
    frame = page.frame_locator("details.replay iframe").first
    frame.locator("body[data-ready='1']").wait_for(state="attached", timeout=10_000)
    frame.locator("#btn-play").click()
    frame.locator("#clock").filter(has_not_text="t = 0.00").wait_for(timeout=5_000)
    page.screenshot(path=str(tmp_path / "report-week3.png"), full_page=True)
    page.close()
    assert errors == []
