"""Fixtures for the replay viewer tests: sample traces and one headless Chromium per module."""

from __future__ import annotations

import importlib.util
import shutil
import tempfile
from pathlib import Path

import pytest

DATA = Path(__file__).resolve().parents[1] / "data"
CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--disable-quic"]


def _synthetic():
    spec = importlib.util.spec_from_file_location("simiam_test_synthetic", DATA / "traces" / "synthetic.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="session")
def synthetic():
    """The synthetic trace generator (tests/data/traces/synthetic.py) as a module."""
    return _synthetic()


@pytest.fixture(scope="module")
def browser_context():
    """A fresh persistent Chromium profile, headless and offline-minded; closed after the module."""
    if not Path(CHROMIUM).exists():
        pytest.skip(f"{CHROMIUM} is absent (apt package 'chromium'); browser tests need it")
    sync_api = pytest.importorskip("playwright.sync_api",
                                   reason="the Python playwright package is not installed")
    profile = tempfile.mkdtemp(prefix="simiam-chromium-")
    with sync_api.sync_playwright() as p:
        ctx = p.chromium.launch_persistent_context(profile, executable_path=CHROMIUM, args=CHROMIUM_ARGS,
                                                   headless=True, viewport={"width": 1280, "height": 760})
        ctx.route("http*://**", lambda route: route.abort())  # the pages must not need the network
        yield ctx
        ctx.close()
    shutil.rmtree(profile, ignore_errors=True)


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
