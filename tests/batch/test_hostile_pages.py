"""A class of hostile students graded as a batch: nothing they control (folder names, printed output,
controller state names, exception text) runs as script in any page the grader writes (each student's
report, its replay pages, the fallback page, summary.html), Gradescope shows it as plain text,
and none of it reaches the instructor's terminal raw."""

from __future__ import annotations

import contextlib
import importlib.util
import io
import json
import sys
import unicodedata
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))

import mistakes  # noqa: E402
from browser import chromium_context  # noqa: E402

MARKUP_ID = "<img src=x onerror=window.__pwned=6>"          # a folder name that is markup
ERROR_ID = "error<svg onload=window.__pwned=7>"             # markup again: the student whose code raises
TERMINAL_ID = "\x1b]0;owned\x07\x1b[2Jansi\r\u202eid<svg onload=window.__pwned=8>"  # escapes and markup
# prints (1), state name (3), exception text (5), the three folder names (6, 7, 8)
SENTINELS = ("window.__pwned = 1", "window.__pwned=3", "window.__pwned=5", "window.__pwned=6",
             "window.__pwned=7", "window.__pwned=8")
HIDDEN = ("Cc", "Cf", "Cs", "Zl", "Zp")  # controls, format (bidi, zero-width), surrogates, separators
# Run in every frame before the page's own scripts: any student script that runs leaves a trace here.
HOOKS = """window.__pwned = null; window.__alerts = [];
for (const name of ["alert", "confirm", "prompt", "print"]) {
  window[name] = (m) => window.__alerts.push(String(m));
}"""


@pytest.fixture(scope="module")
def hostile_class(tmp_path_factory) -> tuple[Path, str, int]:
    """(output folder, what the batch printed on stderr, exit status) for a week-3 class of three."""
    from grader.cli import main

    root = tmp_path_factory.mktemp("hostile")
    klass = root / "class"
    mistakes.build("submissions", "week3_hostile_text", klass, folder_name=MARKUP_ID)
    mistakes.build("submissions", "week3_hostile_error", klass, folder_name=ERROR_ID)
    (klass / f"{TERMINAL_ID}.zip").write_bytes(b"not a zip")  # invalid: a fallback page and a message
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        code = main(["week3", "--batch", str(klass), "--out", str(root / "out"), "--jobs", "1",
                     "--seed", "3"])
    return root / "out", err.getvalue(), code


def pages(out: Path) -> list[Path]:
    """Every page of the batch: the students' reports, summary.html and each run's replay page."""
    return sorted(out.glob("*.html")) + sorted(out.glob("replays/*/*.html"))


def raw_controls(text: str) -> list[str]:
    """Characters that would act on a terminal (controls other than newline, bidi and other format
    characters), as a list to show in the failure."""
    return [repr(c) for c in text if c != "\n" and unicodedata.category(c) in HIDDEN]


def test_the_batch_prints_student_text_only_as_visible_escapes(hostile_class) -> None:
    _, err, code = hostile_class
    assert code == 1  # graded, but not everyone
    assert raw_controls(err) == []
    assert "\\x1b]0;owned\\x07\\x1b[2Jansi\\r\\u202eid<svg" in err  # the id is shown, visibly escaped
    assert raw_controls("\x1b[2J\r\u202e") == ["'\\x1b'", "'\\r'", "'\\u202e'"]  # the check can fail


def test_gradescope_shows_student_text_as_plain_text(hostile_class) -> None:
    out, _, _ = hostile_class
    exports = [json.loads(p.read_text()) for p in (out / "gradescope").glob("*/results.json")]
    assert len(exports) == 3
    for export in exports:
        assert (export["output_format"], export["test_output_format"], export["test_name_format"]) == \
            ("text", "text", "text")


def open_everything(page) -> None:
    """Open every <details> (the collapsed checks, the lazy replays) and wait for each replay to start
    (a replay page of its own included)."""
    page.evaluate("() => document.querySelectorAll('details').forEach(d => d.open = true)")
    if page.evaluate("() => !!document.getElementById('simiam-data')"):
        page.locator("body[data-ready='1']").wait_for(state="attached", timeout=20_000)
    for k in range(page.locator("iframe").count()):
        page.locator("iframe").nth(k).scroll_into_view_if_needed()  # they load lazily, when in view
        page.frame_locator("iframe").nth(k).locator("body[data-ready='1']").wait_for(state="attached",
                                                                                     timeout=20_000)


def injected(page) -> list[str]:
    """Signs that student text ran or became markup, in the page and in every frame: the sentinel set, a
    hooked dialog called, an element the templates never write (img, on* handlers, extra scripts)."""
    found = []
    for frame in page.frames:
        state = frame.evaluate("""() => ({
            pwned: window.__pwned, alerts: window.__alerts,
            imgs: document.querySelectorAll('img').length,
            handlers: [...document.querySelectorAll('*')].flatMap(e => [...e.attributes])
                .filter(a => a.name.startsWith('on')).map(a => a.name + '=' + a.value),
            scripts: [...document.scripts].map(s => s.type || 'js')})""")
        replay = frame.evaluate("() => document.getElementById('simiam-data')?.type")
        expected_scripts = [replay, "js"] if replay else []   # the data (JSON or deflated), the script
        if state["pwned"] is not None or state["alerts"] or state["imgs"] or state["handlers"] or \
                state["scripts"] != expected_scripts:
            found.append(f"{frame.url[:60]}: {state}")
    return found


@pytest.fixture()  # one Chromium at a time: playwright's sync API runs one per thread
def escaping_only_browser():
    """Chromium that ignores the pages' CSP: what it shows is what escaping alone achieves."""
    yield from chromium_context({"width": 1200, "height": 900}, bypass_csp=True)


@pytest.fixture()
def csp_browser():
    yield from chromium_context({"width": 1200, "height": 900})


@pytest.mark.browser
def test_no_page_runs_student_text_even_without_csp(hostile_class, escaping_only_browser) -> None:
    out, _, _ = hostile_class
    escaping_only_browser.add_init_script(HOOKS)
    seen, visible = set(), set()
    for path in pages(out):
        page = escaping_only_browser.new_page()
        page.goto(path.resolve().as_uri())
        page.wait_for_load_state("load")
        open_everything(page)
        for frame in page.frames:  # the replays draw the state name into their status line
            if frame.evaluate("() => !!document.getElementById('simiam-data')"):
                frame.evaluate("() => window.simiam.seek(1)")
        assert injected(page) == [], path.name
        text = page.inner_text("body") + "".join(f.evaluate("() => document.body.innerText")
                                                 for f in page.frames[1:])
        seen |= {s for s in SENTINELS if s in text}
        # and shown as it is: a bidi override or escape sequence appears as \u202e or \x1b, never obeyed
        assert raw_controls(text.replace("\t", " ")) == [], path.name
        visible |= {s for s in ("\\u202e", "\\x1b[2J") if s in text}
        page.close()
    # three students and summary.html, and the replay pages of the two students graded
    assert len(list(out.glob("*.html"))) == 4 and len(pages(out)) > 4
    # every hostile text was shown to its reader, as text: prints, state name, exception, both ids
    assert seen == set(SENTINELS)
    assert visible == {"\\u202e", "\\x1b[2J"}


def _post_render_replace():
    path = ROOT / "tests" / "data" / "report_wrong" / "post_render_replace.py"
    spec = importlib.util.spec_from_file_location("post_render_replace", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.browser
def test_the_check_catches_a_name_replaced_into_rendered_html(hostile_class, escaping_only_browser,
                                                              tmp_path) -> None:
    out, _, _ = hostile_class
    result = next(json.loads(p.read_text()) for p in out.glob("*.json")
                  if p.name != "batch.json" and json.loads(p.read_text()).get("submission") == MARKUP_ID)
    wrong = tmp_path / "wrong.html"
    wrong.write_text(_post_render_replace().report_with_name(result, MARKUP_ID))
    escaping_only_browser.add_init_script(HOOKS)
    page = escaping_only_browser.new_page()
    page.goto(wrong.resolve().as_uri())
    page.wait_for_load_state("load")
    assert injected(page) != []
    page.close()


@pytest.mark.browser
def test_every_page_has_a_csp_that_lets_only_its_own_script_run(hostile_class, csp_browser) -> None:
    out, _, _ = hostile_class
    for path in pages(out):
        page = csp_browser.new_page()
        errors: list[str] = []
        page.on("console", lambda m, errors=errors: errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e, errors=errors: errors.append(str(e)))
        page.goto(path.resolve().as_uri())
        page.wait_for_load_state("load")
        policy = page.get_attribute('meta[http-equiv="Content-Security-Policy"]', "content") or ""
        directives = dict((d.strip().split(" ", 1) + [""])[:2] for d in policy.split(";") if d.strip())
        assert directives.get("default-src") == "'none'", path.name
        assert "unsafe" not in directives.get("script-src", "'none'"), path.name  # no inline, no eval
        open_everything(page)  # the embedded replays still run under the policy they inherit
        assert errors == [], path.name  # no violation: nothing was refused, nothing needed refusing
        page.close()
