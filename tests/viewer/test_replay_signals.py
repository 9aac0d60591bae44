"""The replay draws whatever signals a trace declares: vectors, points and headings as overlays the
student toggles, labels and events beside the state timeline (which controller ran when), numbers as
plots; none of it knows a signal's name in advance. Checked in headless Chromium on a run of the real
simulator with a week-5-like set of signals, and each wrong page in tests/data/viewer_wrong is caught."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

from simiam.viewer import replay
from simiam.viewer.replay import pack_trace, render_replay, write_replay

pytestmark = pytest.mark.browser
DATA = Path(__file__).resolve().parents[1] / "data"
MUTATIONS = json.loads((DATA / "viewer_wrong/mutations.json").read_text())
_spec = importlib.util.spec_from_file_location("simiam_test_switching", DATA / "traces/switching.py")
SWITCHING = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(SWITCHING)


@pytest.fixture(scope="module")
def week5_like():
    return SWITCHING.switching_trace()


def test_the_packed_page_carries_every_declared_signal(week5_like):
    packed = pack_trace(week5_like)
    assert [s["name"] for s in packed["signals"]] == list(SWITCHING.SIGNALS)
    assert packed["signal_data"]["fw_direction"][:2] == [[0, ""], [20, "left"]]
    assert packed["signal_data"]["at_goal"][40:42] == [1, 1] and packed["signal_data"]["switches"][-1] == 2
    assert packed["ending"] == {"reason": "time_up", "t": 3.0, "message": ""}


def overlays_toggle(page) -> bool:
    """Untick u_gtg in the legend: true if it is then off and the drawing changed."""
    before = page.evaluate("() => document.getElementById('world').toDataURL()")
    page.locator("#legend label", has_text="u_gtg").locator("input").click()
    after = page.evaluate("() => document.getElementById('world').toDataURL()")
    off = [o for o in page.evaluate("window.simiam.overlays()") if o["name"] == "u_gtg"][0]["on"] is False
    return off and before != after


def vectors_drawn(page) -> bool:
    """All overlays off, then u_gtg alone on: true if that changes the drawing."""
    for name in ("u_gtg", "u_ao"):
        page.evaluate(f"window.simiam.setOverlay('{name}', false)")
    bare = page.evaluate("() => document.getElementById('world').toDataURL()")
    page.evaluate("window.simiam.setOverlay('u_gtg', true)")
    return page.evaluate("() => document.getElementById('world').toDataURL()") != bare


def timeline_painted(page) -> bool:
    """The timeline band at t = 0.5 s and 1.5 s has the colour of the state that ran then."""
    page.evaluate("window.simiam.seek(2.9)")  # the time cursor away from the samples
    colours = page.evaluate("""() => {
        const c = document.querySelector('.plot.timeline canvas'), g = c.getContext('2d');
        const w = c.getBoundingClientRect().width, s = window.simiam.state(), tEnd = s.plotEnd;
        const ml = s.labelMargins[0];  // the timeline is the first plot; its margin fits its row labels
        const at = t => Array.from(g.getImageData(Math.round(ml + t / tEnd * (w - ml - 4)), 5, 1, 1).data);
        const hex = s => [1, 3, 5].map(k => parseInt(s.slice(k, k + 2), 16));
        return [at(0.5), hex(window.simiam.stateColor('go_to_goal')),
                at(1.5), hex(window.simiam.stateColor('follow_wall'))];
    }""")
    return colours[0][:3] == colours[1] and colours[2][:3] == colours[3]


def test_overlays_timeline_and_plots(open_page, week5_like, tmp_path):
    page, errors = open_page(write_replay(week5_like, tmp_path / "week5.html"))
    page.evaluate("window.simiam.seek(1.5)")
    assert [{k: o[k] for k in ("name", "kind", "on")} for o in page.evaluate("window.simiam.overlays()")] == [
        {"name": "theta_g", "kind": "scalar", "on": False},  # a heading, off where vectors are drawn
        {"name": "u_gtg", "kind": "vector2", "on": True}, {"name": "u_ao", "kind": "vector2", "on": True}]
    titles = page.locator(".plot h2").all_inner_texts()
    assert titles[0].startswith("States and events") and any(t.startswith("d_prog (m)") for t in titles)
    assert any(t.startswith("switches (count)") for t in titles)
    assert "fw_direction left" in page.locator("#status").inner_text()
    assert timeline_painted(page) and vectors_drawn(page)
    page.evaluate("window.simiam.seek(1.5)")
    assert overlays_toggle(page)
    page.screenshot(path=str(tmp_path / "replay-week5.png"))
    assert errors == []


@pytest.mark.parametrize(("mutation", "check"), [
    ("overlay_toggle_ignored", overlays_toggle), ("timeline_paints_nothing", timeline_painted),
    ("vectors_ignored", vectors_drawn)])
def test_checks_catch_wrong_pages(open_page, week5_like, tmp_path, monkeypatch, mutation, check):
    find, replace = MUTATIONS[mutation]
    real_asset = replay._asset
    js = real_asset("static/replay.js")
    assert find in js, f"mutation {mutation} no longer applies to replay.js"
    monkeypatch.setattr(replay, "_asset", lambda name: js.replace(find, replace) if name.endswith(".js")
                        else real_asset(name))
    path = tmp_path / f"{mutation}.html"
    path.write_text(render_replay(week5_like))
    page, _ = open_page(path)
    page.evaluate("window.simiam.seek(1.5)")
    assert not check(page)


def test_a_week4_trace_written_before_signals_were_declared(open_page, tmp_path):
    synthetic = importlib.util.spec_from_file_location("simiam_test_synth_s", DATA / "traces/synthetic.py")
    mod = importlib.util.module_from_spec(synthetic)
    synthetic.loader.exec_module(mod)
    trace = mod.load("week4_wander.json")
    assert "signals" not in trace
    page, errors = open_page(write_replay(trace, tmp_path / "week4.html"))
    assert [(o["name"], o["on"]) for o in page.evaluate("window.simiam.overlays()")] == [
        ("u_ao", True), ("ir_points_wf", True)]  # its theta_g column is all null: nothing to draw
    assert page.locator(".plot h2").first.inner_text().startswith("States")
    assert errors == []
