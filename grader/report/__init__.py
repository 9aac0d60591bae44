"""The grader's HTML report (html.py, jinja2 templates) and the inline SVG plots (svg.py) it and the batch
summary use."""

from grader.report.html import render_report, write_report

__all__ = ["render_report", "write_report"]
