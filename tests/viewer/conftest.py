"""Fixtures for the replay viewer tests: sample traces and one headless Chromium per module."""

from __future__ import annotations

from pathlib import Path

import pytest
from browser import chromium_context, load_synthetic


@pytest.fixture(scope="session")
def synthetic():
    """The synthetic trace generator (tests/data/traces/synthetic.py) as a module."""
    return load_synthetic("simiam_test_synthetic")


@pytest.fixture(scope="module")
def browser_context():
    """A fresh persistent Chromium profile, headless and offline-minded; closed after the module."""
    yield from chromium_context({"width": 1280, "height": 760})


class PageErrors(list):
    """Console errors and uncaught exceptions seen by a page, in order."""


@pytest.fixture()
def open_page(browser_context):
    """open_page(path) -> (page, errors): load a local HTML file and wait for the replay to be ready."""
    pages = []

    def _open(path: Path, ready: str | None = "body[data-ready='1']"):
        page = browser_context.new_page()
        errors = PageErrors()
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(Path(path).resolve().as_uri())
        if ready:
            page.wait_for_selector(ready, state="attached", timeout=10_000)
        pages.append(page)
        return page, errors

    yield _open
    for page in pages:
        page.close()
