"""Wrong on purpose: what the batch did before, a student's folder name put into the rendered report by a
string replace (the report was rendered with the temporary path, then the path replaced by the name).
tests/batch/test_hostile_pages.py shows that its browser check catches this page."""

from grader.report import render_report

TEMPORARY = "/tmp/simiam-batch-x/submission"


def report_with_name(result: dict, name: str) -> str:
    html = render_report({**result, "submission": TEMPORARY}, {})
    return html.replace(TEMPORARY, name)
