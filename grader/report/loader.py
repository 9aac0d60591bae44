"""Where the report's templates come from: the package's `templates/`, taking a template's precompiled code
(grader/report/compiled/, made by `python -m grader.report.precompiled`) when its stamp matches
(simiam.viewer.precompiled says when stored code is used)."""

from __future__ import annotations

from collections.abc import MutableMapping
from pathlib import Path
from typing import Any

import jinja2

from simiam.viewer import precompiled

COMPILED = Path(__file__).with_name("compiled")
TEMPLATES = ("report.html.j2", "report.css.j2")


def module_name(template: str) -> str:
    """The stored module of a report template: report.html.j2 -> grader.report.compiled.report_html_j2."""
    return "grader.report.compiled." + template.replace(".", "_").replace("-", "_")


class PrecompiledLoader(jinja2.PackageLoader):
    """The report's PackageLoader, taking a template's stored code when its stamp matches."""

    def load(self, environment: jinja2.Environment, name: str,
             globals: MutableMapping[str, Any] | None = None) -> jinja2.Template:
        source, filename, uptodate = self.get_source(environment, name)
        if name not in TEMPLATES:
            return super().load(environment, name, globals)
        return precompiled.template(environment, source, module_name(name), name, filename, globals, uptodate)
