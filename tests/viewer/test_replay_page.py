"""The replay page as text: self-contained, escaped, compact, and clear about bad input (no browser)."""

from __future__ import annotations

import importlib.util
import json
import math
import re
from pathlib import Path

import pytest

from simiam.viewer.replay import TraceFormatError, pack_trace, render_replay, write_replay

WRONG = Path(__file__).resolve().parents[1] / "data" / "viewer_wrong"
EVIL = "</script><script>window.pwned = 1</script>"


def _wrong():
    spec = importlib.util.spec_from_file_location("simiam_viewer_wrong", WRONG / "naive_embed.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def script_elements_are_closed_once(html: str) -> bool:
    """True if no student-controlled text can open a new <script>: exactly the page's own two elements."""
    return len(re.findall(r"<script\b", html, flags=re.I)) == 2 and "window.pwned" not in html.split(
        'id="simiam-data">', 1)[1].split("</script>", 1)[1].split("<script>", 1)[0]


def no_network(html: str) -> bool:
    """No external fetches: no src/href to http(s) or protocol-relative URLs, no @import."""
    return not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//|@import|url\(\s*["']?https?:""", html, re.I)


def test_page_is_self_contained(synthetic):
    html = render_replay(synthetic.load("week3_goal.json"))
    assert html.startswith("<!doctype html>")
    assert no_network(html)
    assert "window.simiam" in html and "#toolbar" in html  # script and style are inlined
    assert not no_network('<script src="https://cdn.example/x.js"></script>')  # the check can fail


def test_student_text_cannot_break_out_of_the_data_element(synthetic):
    trace = synthetic.load("week3_goal.json")
    trace["steps"]["state"] = [EVIL] * len(trace["steps"]["t"])
    trace["meta"]["submission"] = EVIL
    html = render_replay(trace)
    assert script_elements_are_closed_once(html)
    assert "&lt;/script&gt;" in html  # the title is escaped, not dropped
    naive = html.replace(html.split('id="simiam-data">', 1)[1].split("</script>", 1)[0],
                         _wrong().naive_script_json(pack_trace(trace)))
    assert not script_elements_are_closed_once(naive)


def test_packing_is_columnar_rounded_and_json_safe(synthetic):
    trace = synthetic.load("week4_wander.json")
    trace["steps"]["x"][3] = float("nan")
    trace["steps"]["theta_g"] = [None] * len(trace["steps"]["t"])
    packed = pack_trace(trace)
    steps = packed["steps"]
    n = len(trace["steps"]["t"])
    assert all(len(v) == n for v in steps.values())
    assert steps["x"][3] is None  # NaN would make the page's JSON invalid
    sig = packed["signal_data"]
    assert "theta_g" not in sig and "theta_g" not in [s["name"] for s in packed["signals"]]  # all null
    assert steps["x"][10] == round(trace["steps"]["x"][10], 4)
    assert steps["ir2"][10] == round(trace["steps"]["ir_range"][10][2], 4)
    assert sig["ir_points_wf"]["x"][4][10] == round(trace["steps"]["ir_points_wf"][10][0][4], 4)
    assert sig["u_ao"]["y"][10] == round(trace["steps"]["u_ao"][10][1], 4)
    assert packed["states"][0] == [0, "avoid_obstacles"]
    json.dumps(packed, allow_nan=False)


def test_states_are_run_length_encoded(synthetic):
    trace = synthetic.load("week3_goal.json")
    states = trace["steps"]["state"]
    first_stop = states.index("stop")
    assert "go_to_goal" not in states[first_stop:]  # the sample stops for good
    assert pack_trace(trace)["states"] == [[0, "go_to_goal"], [first_stop, "stop"]]


def test_sixty_second_run_stays_under_one_megabyte(synthetic, tmp_path):
    trace = synthetic.make_trace(week=4, seconds=60.0, dt=0.033, stop_on_collision=False)
    assert len(trace["steps"]["t"]) == 1819
    path = write_replay(trace, tmp_path / "sub" / "replay.html")
    size = path.stat().st_size
    print(f"60 s week-4 replay: {size} bytes ({size / 1024:.0f} KiB)")
    assert size < 1_000_000
    assert len(_wrong().naive_page(trace).encode()) >= 1_000_000  # pasting the raw trace would not fit


@pytest.mark.parametrize(("trace", "words"), [
    ([1, 2], "JSON object"),
    ({"format": "other/2", "steps": {}}, "other/2"),
    ({"robot": {"base_plate": [[0, 0]]}}, "'steps'"),
    ({"steps": {"t": [0.0], "x": [0.0]}, "robot": {"base_plate": [[0, 0]]}}, "y, theta"),
    ({"steps": {"t": [0.0, 1.0], "x": [0.0], "y": [0, 0], "theta": [0, 0]},
      "robot": {"base_plate": [[0, 0]]}}, "steps.x has 1 rows"),
    ({"steps": {"t": [0.0], "x": [0.0], "y": [0.0], "theta": [0.0]}}, "base_plate"),
])
def test_bad_traces_get_a_plain_message(trace, words):
    with pytest.raises(TraceFormatError, match=re.escape(words)):
        render_replay(trace)


def test_minimal_trace_renders(synthetic):
    """Only the required columns: the page still builds (no goal, no estimate, no IR)."""
    trace = {"steps": {"t": [0.0, 0.033], "x": [0.0, 0.01], "y": [0.0, 0.0], "theta": [0.0, math.pi]},
             "robot": {"base_plate": [[0.05, 0.05], [-0.05, 0.05], [-0.05, -0.05]]}}
    packed = pack_trace(trace)
    assert packed["goal"] is None and packed["steps"]["x_est"] == [None, None]
    assert "simiam replay" in render_replay(trace)


def test_command_line_writes_a_page_or_says_what_is_wrong(synthetic, tmp_path, capsys):
    from simiam.viewer.replay import main

    good = tmp_path / "run.json"
    good.write_text(json.dumps(synthetic.load("week3_goal.json")))
    assert main([str(good)]) == 0 and (tmp_path / "run.html").stat().st_size > 10_000
    broken = tmp_path / "broken.json"
    broken.write_text('{"steps":\n  [1, 2,]}')
    assert main([str(broken)]) == 2
    assert f"{broken}, line 2: not valid JSON" in capsys.readouterr().err
    other = tmp_path / "other.json"
    other.write_text('{"format": "something/9"}')
    assert main([str(other)]) == 2
    assert "not a simiam trace: trace format is 'something/9'" in capsys.readouterr().err
