"""similarity.html in headless Chromium at 1024 px: no element outside the window, with a 3000-character
line in a copied block and the longest student ids; the kept wrong page (tests/data/similarity/wrong_page.py)
runs off it."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest
from browser import chromium_context
from similarity_class import DATA

from grader.similarity import page as similarity_page
from grader.similarity.command import run

pytestmark = pytest.mark.browser

OUTSIDE = """() => [...document.body.querySelectorAll('*')].map(e => [e, e.getBoundingClientRect()])
  .filter(([e, r]) => r.width > 0 && (r.left < -0.5 || r.right > innerWidth + 0.5))
  .map(([e, r]) => e.tagName + ' ' + Math.round(r.left) + '..' + Math.round(r.right) + ' '
       + (e.textContent || '').slice(0, 40))"""


def _wide_class(week3_class: Path) -> Path:
    """The week-3 class (this module's own) plus two long-named students sharing a block with a
    3000-character line."""
    long_line = "        vel_r = vel_r_d + " + "+".join(["vel_rl_max"] * 270) + "\n"
    text = (DATA / "independent" / "chen" / "qb_supervisor.py").read_text()
    text = text.replace("        top = robot.max_vel\n", "        top = robot.max_vel\n" + long_line)
    for sid in ("a" * 120, "b" * 120):
        (week3_class / sid).mkdir(exist_ok=True)
        (week3_class / sid / "qb_supervisor.py").write_text(text)
    return week3_class


def _outside(uris: list[str]) -> list[tuple[list[str], int]]:
    """For each page: the elements (tag, left..right, text) outside a 1024 px window, and its width."""
    seen = []
    for context in chromium_context({"width": 1024, "height": 800}):
        page = context.new_page()
        for uri in uris:
            page.goto(uri)
            seen.append((page.evaluate(OUTSIDE), page.evaluate("document.documentElement.scrollWidth")))
    return seen


def test_page_fits_1024(week3_class: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    folder = _wide_class(week3_class)
    report = run(3, folder, tmp_path / "out")
    assert ("a" * 120, "b" * 120) in [(p["a"], p["b"]) for p in report["pairs"]], report["pairs"]
    spec = importlib.util.spec_from_file_location("wrong_page", DATA.parent / "wrong_page.py")
    wrong = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(wrong)
    monkeypatch.setattr(similarity_page, "_TEMPLATE", wrong.wrong_template(similarity_page._TEMPLATE))
    run(3, folder, tmp_path / "wrong")

    (found, width), (wrong_found, wrong_width) = _outside(
        [(tmp_path / name / "similarity.html").as_uri() for name in ("out", "wrong")])
    assert (found, width) == ([], 1024)
    assert wrong_found and wrong_width > 1024, "the wrong page must run off the window (else: proves nothing)"
