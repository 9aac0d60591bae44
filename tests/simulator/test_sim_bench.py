"""`simiam bench`: the JSON it prints (no timing assertions: the figures are only printed), and that the
reference avoid-obstacles brain it times really drives the week-4 world without crashing."""

from __future__ import annotations

import json
from types import SimpleNamespace

import pytest

from instructor_tools.reference_brains import AvoidObstaclesBrain
from simiam.bench import main
from simiam.course.weeks import spec_for_week
from simiam.simulator import Simulator
from simiam.world import load_world


def test_bench_json(capsys):
    assert main(SimpleNamespace(json=True, seconds=0.99)) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("steps_per_second", "us_per_step", "steps", "dt", "real_time_factor"):
        assert isinstance(out[key], (int, float)) and out[key] > 0, key
    assert out["steps"] == 30 and out["dt"] == 0.033
    assert abs(out["us_per_step"] * out["steps_per_second"] - 1e6) < 1e-3


@pytest.mark.parametrize("seconds", [-1.0, 0.0, float("nan"), 1e9])
def test_bench_rejects_bad_seconds(capsys, seconds):
    assert main(SimpleNamespace(json=False, seconds=seconds)) == 2
    assert "--seconds" in capsys.readouterr().err


def test_reference_avoid_obstacles_drives_without_crashing():
    spec = spec_for_week(4)
    sim = Simulator(load_world("week4"), AvoidObstaclesBrain(spec), spec)
    trace = sim.run(seconds=60.0)
    assert trace.collision is None and len(trace) == 1819
    xs, ys = trace.steps["x"], trace.steps["y"]
    assert max(xs) - min(xs) > 0.5 or max(ys) - min(ys) > 0.5  # it moved about, not just in place
    raws = [v for row in trace.steps["ir_raw"] for v in row]
    assert min(raws) == 133 and max(raws) > 300  # it sees nothing at times and comes near obstacles
