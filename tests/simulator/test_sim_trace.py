"""Trace (Seam 2): JSON round trip, CSV columns, row 0 = the state before the first step."""

from __future__ import annotations

import csv
import json

import pytest

from simiam.course.weeks import spec_for_week
from simiam.simulator import ConstantBrain, Simulator
from simiam.trace import COLUMNS, Trace
from simiam.world import load_world


@pytest.fixture(scope="module")
def trace():
    sim = Simulator(load_world("week4"), ConstantBrain(6.0, 4.0), spec_for_week(4), dt=0.05)
    return sim.run(seconds=3.0, stop_on_collision=False)


def test_header_and_row0(trace):
    data = trace.to_json()
    assert data["format"] == "simiam-trace/1" and data["week"] == 4 and data["dt"] == 0.05
    assert data["start"] == [0.0, 0.0, 0.0] and len(data["world"]["obstacles"]) == 6
    assert data["robot"]["ir_spread"] == 0.10471975511965977 and len(data["robot"]["base_plate"]) == 13
    s = data["steps"]
    assert set(s) == set(COLUMNS) and all(len(s[c]) == len(trace) for c in COLUMNS)
    row0 = (s["t"][0], s["x"][0], s["ticks_r"][0], s["vel_r"][0], s["collided"][0])
    assert row0 == (0.0, 0.0, 0, 0.0, False)
    assert s["ir_raw"][0] == [296, 177, 133, 133, 133]  # the original's start reading in the week-4 world
    assert s["x_est"][0] == 0.0 and s["state"][1] == "constant" and s["vel_r"][1] == 6.0
    assert data["seconds"] == pytest.approx(3.0)


def test_json_round_trip(trace, tmp_path):
    csv_path, json_path = trace.write(tmp_path)
    text = json_path.read_text()
    back = Trace.from_json(text)
    assert back.to_json() == json.loads(text) == json.loads(json.dumps(trace.to_json()))
    with pytest.raises(ValueError, match="simiam-trace/1"):
        Trace.from_json({"format": "other"})


def test_csv_is_flat(trace, tmp_path):
    csv_path, _ = trace.write(tmp_path, stem="run")
    with csv_path.open() as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(trace)
    assert rows[0]["ir_raw_1"] == "296" and rows[0]["theta_g"] == "" and rows[5]["ir_points_wf_y5"] == ""
    assert float(rows[-1]["x"]) == trace.steps["x"][-1]  # floats are written to round-trip
