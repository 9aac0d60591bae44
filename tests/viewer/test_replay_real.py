"""The replay page from real simulator traces (simiam.simulator), not only the synthetic samples."""

from __future__ import annotations

from pathlib import Path

import pytest

from simiam.viewer.replay import pack_trace, write_replay

ROOT = Path(__file__).resolve().parents[2]


def constant_speed_trace(seconds: float = 20.0) -> dict:
    """Week-4 world, both wheels constant (a slow left arc) until it hits something."""
    from simiam.course.weeks import spec_for_week
    from simiam.simulator import ConstantBrain, Simulator
    from simiam.world import load_world

    sim = Simulator(load_world("week4"), ConstantBrain(5.0, 4.0), spec=spec_for_week(4), dt=0.033)
    return sim.run(seconds=seconds).to_json()


def solution_trace(week: int, seconds: float) -> dict:
    """The reference solution driving the week's scenario (the supervisor's debug values included)."""
    from simiam.control.local_brain import LocalBrain
    from simiam.course.loader import load_submission
    from simiam.course.weeks import get_week
    from simiam.simulator import Simulator
    from simiam.world import load_world

    cfg = get_week(week)
    sub = load_submission(ROOT / "solutions" / f"week{week}", cfg)
    sim = Simulator(load_world(cfg.world), LocalBrain(sub, cfg), spec=cfg.spec, dt=0.033, start=cfg.start)
    return sim.run(seconds=seconds).to_json()


def test_real_collision_trace_packs():
    trace = constant_speed_trace()
    assert trace["collision"] is not None
    packed = pack_trace(trace)
    n = len(trace["steps"]["t"])
    assert packed["collision"]["t"] == pytest.approx(trace["collision"]["t"], abs=1e-4)
    assert len(packed["steps"]["ir0"]) == n and len(packed["robot"]["base_plate"]) == 13


def test_real_sixty_second_week4_run_is_under_one_megabyte(tmp_path):
    trace = solution_trace(4, 60.0)
    assert len(trace["steps"]["t"]) == 1819
    size = write_replay(trace, tmp_path / "week4.html").stat().st_size
    print(f"real 60 s week-4 solution replay: {size} bytes")
    assert size < 1_000_000


@pytest.mark.browser
def test_real_trace_in_the_browser(open_page, tmp_path):
    trace = constant_speed_trace()
    page, errors = open_page(write_replay(trace, tmp_path / "crash.html"))
    page.evaluate("window.simiam.seek(1e9)")
    assert f"collided at t = {trace['collision']['t']:.2f} s" in page.inner_text("#status")
    s0 = page.evaluate("window.simiam.state()")
    page.evaluate("window.simiam.seek(0)")
    assert page.evaluate("window.simiam.state()")["robotScreenXY"] != s0["robotScreenXY"]
    page.screenshot(path=str(tmp_path / "replay-real-crash.png"))
    assert errors == []
