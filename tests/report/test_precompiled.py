"""The report's precompiled templates (grader/report/precompiled.py): used only when made from exactly the
template on disk by this jinja2 with these options, and the page is the same either way."""

from __future__ import annotations

import jinja2
import pytest

from grader.report import html as report_html
from grader.report import precompiled
from grader.report.precompiled import PrecompiledLoader
from tests.report.test_report_html import student_markup_is_inert


def _env(loader: jinja2.BaseLoader) -> jinja2.Environment:
    """An environment with the report's options and another loader."""
    env = report_html._env().overlay(loader=loader)
    env.cache = {}
    return env


def _page(env: jinja2.Environment, result: dict, traces: dict) -> str:
    views = [report_html._check_view(c, traces, "inline", {}, set()) for c in result["checks"]]
    summary = report_html._summary(result, views)
    return env.get_template("report.html.j2").render(summary=summary, checks=views, csp="default-src 'none'")


def test_the_stored_modules_are_up_to_date(capsys):
    """Fails while a template (or the report's environment, or jinja2) changed without regenerating."""
    assert precompiled.main(["--check"]) == 0, capsys.readouterr().out


def test_the_stored_code_is_used_and_renders_the_same_page(week3_result, monkeypatch):
    result, traces = week3_result
    result = {**result, "submission": "<script>window.pwned = 1</script><img src=x>"}
    from_source = _page(_env(jinja2.PackageLoader("grader.report", "templates")), result, traces)

    def no_compiling(*_args, **_kwargs):
        raise AssertionError("compiled from source although the stored code is up to date")

    monkeypatch.setattr(jinja2.Environment, "compile", no_compiling)
    stored = _page(_env(PrecompiledLoader("grader.report", "templates")), result, traces)
    assert stored == from_source
    assert student_markup_is_inert(stored)


class _Edited(PrecompiledLoader):
    """The report's templates with the page title edited on disk and not regenerated."""

    def get_source(self, environment, template):
        source, filename, uptodate = super().get_source(environment, template)
        return source.replace("<h1>Week", "<h1>Edited week"), filename, uptodate


def test_a_template_edited_after_precompiling_is_compiled_from_its_text(week3_result):
    result, traces = week3_result
    page = _page(_env(_Edited("grader.report", "templates")), result, traces)
    assert "<h1>Edited week 3 feedback</h1>" in page


@pytest.mark.parametrize("change", ["jinja2 version", "environment options"])
def test_stored_code_for_another_jinja2_or_other_options_is_not_used(week3_result, monkeypatch, change):
    result, traces = week3_result
    compiled = []
    compile_from_source = jinja2.Environment.compile

    def spy(self, source, name=None, filename=None, raw=False, defer_init=False):
        compiled.append(name)
        return compile_from_source(self, source, name, filename, raw, defer_init)

    monkeypatch.setattr(jinja2.Environment, "compile", spy)
    env = _env(PrecompiledLoader("grader.report", "templates"))
    if change == "jinja2 version":
        monkeypatch.setattr(jinja2, "__version__", "99.0")
    else:
        env.trim_blocks = False
    _page(env, result, traces)
    assert compiled == ["report.html.j2", "report.css.j2"]


def test_the_replay_page_uses_its_stored_code_and_renders_the_same(week3_result, monkeypatch):
    from simiam.viewer import replay

    _, traces = week3_result
    trace = {**next(iter(traces.values())), "meta": {"check_label": "</script><script>window.pwned=1"}}
    stored_template = replay._template
    compiled_here = replay._env().from_string(replay._asset(replay.TEMPLATE))
    monkeypatch.setattr(replay, "_template", lambda: compiled_here)
    from_source = replay.render_replay(trace, title="</title><script>window.pwned=2</script>")
    monkeypatch.setattr(replay, "_template", stored_template)

    def no_compiling(*_args, **_kwargs):
        raise AssertionError("compiled from source although the stored code is up to date")

    monkeypatch.setattr(jinja2.Environment, "compile", no_compiling)
    replay._template.cache_clear()
    try:
        page = replay.render_replay(trace, title="</title><script>window.pwned=2</script>")
    finally:
        replay._template.cache_clear()
    assert page == from_source
    assert "<script>window.pwned" not in page


def test_an_edited_replay_template_is_compiled_from_its_text(week3_result, monkeypatch):
    from simiam.viewer import replay

    _, traces = week3_result
    asset = replay._asset
    edited = asset(replay.TEMPLATE).replace("<title>", "<title>Edited ")
    monkeypatch.setattr(replay, "_asset", lambda name: edited if name == replay.TEMPLATE else asset(name))
    replay._template.cache_clear()
    try:
        assert "<title>Edited " in replay.render_replay(next(iter(traces.values())))
    finally:
        replay._template.cache_clear()
