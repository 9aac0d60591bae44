"""The replay page in headless Chromium: it plays, zooms, pans, follows and seeks like the original GUI."""
# Predicates are arrow functions, not bare expressions: playwright evaluates a bare expression string with
# eval(), which the page's Content-Security-Policy (no unsafe-eval) refuses.

from __future__ import annotations

import json
from pathlib import Path

import pytest

from simiam.viewer import replay
from simiam.viewer.replay import render_replay, write_replay

pytestmark = pytest.mark.browser
WRONG = Path(__file__).resolve().parents[1] / "data" / "viewer_wrong"
MUTATIONS = json.loads((WRONG / "mutations.json").read_text())


def state(page) -> dict:
    return page.evaluate("window.simiam.state()")


def canvas_centre(s: dict) -> tuple[float, float]:
    left, top, w, h = s["canvasRect"]
    return left + w / 2, top + h / 2


def plays_and_moves(page) -> bool:
    """Play from t = 0 at 8x; true if time advances past 1 s and the robot's screen position changes."""
    page.evaluate("window.simiam.seek(0); window.simiam.setSpeed(8)")
    before = state(page)
    page.click("#btn-play")
    try:
        page.wait_for_function("() => window.simiam.state().t > 1.0", timeout=3_000)
    except Exception:
        return False
    after = state(page)
    page.evaluate("window.simiam.pause()")
    return after["t"] > before["t"] and after["robotScreenXY"] != before["robotScreenXY"]


def follows(page) -> bool:
    """Click the robot, play: true if the view follows and the robot stays at the canvas centre."""
    page.evaluate("window.simiam.home(); window.simiam.seek(0.5); window.simiam.setSpeed(8)")
    x, y = state(page)["robotScreenXY"]
    page.mouse.click(x, y)
    if not state(page)["following"]:
        return False
    page.evaluate("window.simiam.play()")
    try:
        page.wait_for_function("() => window.simiam.state().t > 3.0", timeout=3_000)
    except Exception:
        return False
    s = state(page)
    page.evaluate("window.simiam.pause()")
    cx, cy = canvas_centre(s)
    return abs(s["robotScreenXY"][0] - cx) < 1.0 and abs(s["robotScreenXY"][1] - cy) < 1.0


def wheel_zooms(page) -> bool:
    page.evaluate("window.simiam.home()")
    z0 = state(page)["zoom"]
    x, y = canvas_centre(state(page))
    page.mouse.move(x + 40, y + 30)
    page.mouse.wheel(0, -400)
    try:
        page.wait_for_function(f"() => window.simiam.state().zoom > {z0} * 1.2", timeout=2_000)
    except Exception:
        return False
    return True


def legend_clear(page) -> bool:
    """At home: true if every wall ends above the legend's top and the world still starts on the canvas."""
    page.evaluate("() => window.simiam.home()")
    walls = page.evaluate("""() => window.simiam.trace.world.obstacles.flat()
        .map(p => window.simiam.worldToScreen(p[0], p[1]))""")
    legend = page.locator("#legend").bounding_box()
    canvas = page.locator("#world").bounding_box()
    return bool(walls) and legend["height"] > 0 and max(y for _, y in walls) <= legend["y"] and \
        min(y for _, y in walls) >= canvas["y"]


@pytest.fixture(scope="module")
def week4_page_path(tmp_path_factory, synthetic):
    return write_replay(synthetic.load("week4_wander.json"), tmp_path_factory.mktemp("replay") / "week4.html")


def test_loads_plays_and_moves(open_page, week4_page_path, tmp_path):
    page, errors = open_page(week4_page_path)
    s = state(page)
    assert s["rows"] == 607 and s["t"] == 0 and not s["playing"]
    assert plays_and_moves(page)
    page.evaluate("window.simiam.seek(12.0)")
    shot = tmp_path / "replay-week4.png"
    page.screenshot(path=str(shot))
    assert shot.stat().st_size > 10_000
    assert errors == []


def test_zoom_buttons_wheel_and_drag_pan(open_page, week4_page_path):
    page, errors = open_page(week4_page_path)
    z0 = state(page)["zoom"]
    page.click("#btn-zoom-in")
    assert state(page)["zoom"] == pytest.approx(z0 * 1.25)
    page.click("#btn-zoom-out")
    page.click("#btn-zoom-out")
    assert state(page)["zoom"] == pytest.approx(z0 * 0.8)
    assert wheel_zooms(page)
    page.evaluate("window.simiam.home()")
    c0 = state(page)["center"]
    x, y = canvas_centre(state(page))
    page.mouse.move(x + 200, y + 200)  # empty floor, away from the robot
    page.mouse.down()
    page.mouse.move(x + 260, y + 160, steps=5)
    page.mouse.up()
    c1 = state(page)["center"]
    zoom = state(page)["zoom"]
    assert c1[0] == pytest.approx(c0[0] - 60 / zoom, abs=1e-6)  # dragging right moves the view left
    assert c1[1] == pytest.approx(c0[1] - 40 / zoom, abs=1e-6)  # dragging up moves the view down
    page.click("#btn-home")
    assert state(page)["center"] == pytest.approx(c0) and state(page)["zoom"] == pytest.approx(z0)
    assert errors == []


def test_click_robot_to_follow(open_page, week4_page_path):
    page, errors = open_page(week4_page_path)
    assert follows(page)
    x, y = canvas_centre(state(page))
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 50, y, steps=3)  # panning ends following, as dragging the view should
    page.mouse.up()
    assert not state(page)["following"]
    assert errors == []


def test_slider_and_keyboard_seek(open_page, week4_page_path):
    page, errors = open_page(week4_page_path)
    page.evaluate("""() => { const s = document.getElementById('slider'); s.value = '300';
                             s.dispatchEvent(new Event('input', {bubbles: true})); }""")
    s = state(page)
    assert s["index"] == 300 and s["t"] == pytest.approx(300 * 0.033, abs=1e-3)
    page.locator("#world").focus()
    page.keyboard.press("ArrowRight")
    assert state(page)["index"] == 301
    page.keyboard.press("Shift+ArrowLeft")
    assert state(page)["index"] == 301 - round(1 / 0.033)
    page.keyboard.press(" ")
    assert state(page)["playing"]
    page.keyboard.press(" ")
    assert not state(page)["playing"]
    shown = page.evaluate("window.simiam.trace.steps.t[window.simiam.state().index]")
    assert page.inner_text("#clock").startswith(f"t = {shown:.2f} /")
    page.select_option("#speed", "4")
    assert state(page)["speed"] == 4
    page.click("#btn-rewind")                                   # the original's Rewind: back to the start
    assert state(page)["index"] == 0 and state(page)["t"] == 0
    page.evaluate("window.simiam.seek(5.0)")
    page.click("#btn-follow")                                   # the follow button, as clicking the robot
    s = state(page)
    cx, cy = canvas_centre(s)
    assert s["following"] and abs(s["robotScreenXY"][0] - cx) < 1.0 and abs(s["robotScreenXY"][1] - cy) < 1.0
    page.click("#btn-follow")
    assert not state(page)["following"]
    plot = page.locator(".plot canvas").first.bounding_box()  # clicking a plot seeks to that time
    page.mouse.click(plot["x"] + plot["width"] - 6, plot["y"] + plot["height"] / 2)
    assert state(page)["t"] > 0.9 * state(page)["tEnd"]
    assert errors == []


def test_collision_and_student_text(open_page, synthetic, tmp_path):
    trace = synthetic.load("week3_crash.json")
    trace["steps"]["state"] = ["</script><script>window.pwned = 1</script>"] * len(trace["steps"]["t"])
    page, errors = open_page(write_replay(trace, tmp_path / "crash.html"))
    page.evaluate("window.simiam.seek(100)")
    assert page.evaluate("window.pwned") is None
    assert "collided at t = 6.73 s" in page.inner_text("#status")
    assert "</script>" in page.inner_text("#status")  # shown as text, not run
    assert page.locator("#marks .mark").count() == 1
    # drag the view until the crash sits 30 px from the canvas's right edge: its label must stay on the canvas
    crash_x, crash_y = page.evaluate("window.simiam.worldToScreen(...window.simiam.trace.collision.pose)")
    canvas_left, _, canvas_w, _ = state(page)["canvasRect"]
    page.mouse.move(crash_x - 100, crash_y + 60)
    page.mouse.down()
    page.mouse.move(canvas_left + canvas_w - 130, crash_y + 60, steps=4)
    page.mouse.up()
    left, width = state(page)["collisionLabel"]
    assert left >= 0 and left + width <= canvas_w
    page.screenshot(path=str(tmp_path / "replay-crash.png"))
    assert errors == []


@pytest.mark.parametrize(("mutation", "check"), [
    ("play_does_not_advance", plays_and_moves), ("follow_does_not_centre", follows),
    ("wheel_ignored", wheel_zooms), ("legend_over_walls", legend_clear)])
def test_checks_catch_wrong_pages(open_page, synthetic, tmp_path, monkeypatch, mutation, check):
    find, replace = MUTATIONS[mutation]
    real_asset = replay._asset
    js = real_asset("static/replay.js")
    assert find in js, f"mutation {mutation} no longer applies to replay.js"
    monkeypatch.setattr(replay, "_asset", lambda name: js.replace(find, replace) if name.endswith(".js")
                        else real_asset(name))
    path = tmp_path / f"{mutation}.html"
    path.write_text(render_replay(synthetic.load("week4_wander.json")))
    page, _ = open_page(path)
    assert not check(page)


@pytest.mark.parametrize("viewport", [{"width": 1280, "height": 760}, {"width": 700, "height": 900}])
def test_at_home_the_legend_is_clear_of_the_walls(open_page, synthetic, tmp_path, viewport):
    page, errors = open_page(write_replay(synthetic.load("week3_goal.json"), tmp_path / "walls.html"))
    page.set_viewport_size(viewport)
    # the page lays out again on its resize event, which the browser fires before its next frame: wait
    # for that frame (two, to be sure), else a loaded machine measures the layout of the old size
    page.wait_for_function("w => window.innerWidth === w", arg=viewport["width"])
    page.evaluate("() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
    assert legend_clear(page)
    assert errors == []
