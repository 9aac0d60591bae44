"""Wrong on purpose: the report rendered with autoescape off. tests/report/test_report_html.py shows its
escaping check catches this (a student's message would run as script in the instructor's browser)."""

import jinja2

from grader.report import html


def render_unescaped(result: dict, traces: dict) -> str:
    env = jinja2.Environment(loader=jinja2.PackageLoader("grader.report", "templates"), autoescape=False,
                             undefined=jinja2.ChainableUndefined)
    env.filters["num"] = html._num
    checks = [html._check_view(c, traces, "none", {}, set()) for c in result["checks"]]
    return env.get_template("report.html.j2").render(summary=html._summary(result, checks), checks=checks)
