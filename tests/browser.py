"""Shared by the browser tests (tests/viewer, tests/report): Debian's Chromium driven by playwright, offline,
and the synthetic trace generator they render."""

from __future__ import annotations

import importlib.util
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

DATA = Path(__file__).resolve().parent / "data"
CHROMIUM = "/usr/bin/chromium"
# without the background-networking flags Chromium keeps trying to reach the network at every start
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--disable-quic"]


def chromium_context(viewport: dict, bypass_csp: bool = False) -> Iterator:
    """Yield a fresh persistent Chromium profile, headless, with every http(s) request refused; skips the
    test when Chromium or playwright is absent. Use as the body of a generator fixture. `bypass_csp`
    ignores the pages' Content-Security-Policy (to show that escaping alone keeps student text inert)."""
    if not Path(CHROMIUM).exists():
        pytest.skip(f"{CHROMIUM} is absent (apt package 'chromium'); browser tests need it")
    sync_api = pytest.importorskip("playwright.sync_api",
                                   reason="the Python playwright package is not installed")
    profile = tempfile.mkdtemp(prefix="simiam-chromium-")
    with sync_api.sync_playwright() as p:
        ctx = p.chromium.launch_persistent_context(profile, executable_path=CHROMIUM, args=CHROMIUM_ARGS,
                                                   headless=True, viewport=viewport, bypass_csp=bypass_csp)
        ctx.route("http*://**", lambda route: route.abort())  # the pages must not need the network
        yield ctx
        ctx.close()
    shutil.rmtree(profile, ignore_errors=True)


def solution_trace(week: int, seconds: float) -> dict:
    """The course's solution of `week` driving the week's world for `seconds`, recording the week's own
    debug signals (as `simiam run` does): the pictures of every week, from real runs."""
    from simiam.control.local_brain import LocalBrain
    from simiam.course.loader import load_submission
    from simiam.course.weeks import get_week
    from simiam.signals import week_signals
    from simiam.simulator import Simulator
    from simiam.world import load_world

    cfg = get_week(week)
    sub = load_submission(DATA.parent.parent / "solutions" / f"week{week}", cfg)
    sim = Simulator(load_world(cfg.world), LocalBrain(sub, cfg), spec=cfg.spec, dt=0.033, start=cfg.start,
                    signals=week_signals(cfg))
    return sim.run(seconds=seconds).to_json()


def load_synthetic(module_name: str) -> ModuleType:
    """The synthetic trace generator (tests/data/traces/synthetic.py) as a module."""
    spec = importlib.util.spec_from_file_location(module_name, DATA / "traces" / "synthetic.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
