"""The report's plots of declared signals and states (grader/report/signal_plots.py): drawn by name from
the trace's own header, none known in advance; student state names escaped; a check asks for them in
`Check.plots`."""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path
from xml.etree import ElementTree

import pytest

from grader.report.html import render_report
from grader.report.signal_plots import declared_plots, signals_svg, state_color, states_svg

DATA = Path(__file__).resolve().parents[1] / "data"
EVIL_STATE = "<script>window.pwned=1</script>"


def _module(name: str, path: Path):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


SWITCHING = _module("simiam_test_switching_r", DATA / "traces/switching.py")


@pytest.fixture(scope="module")
def trace():
    return SWITCHING.switching_trace()


def _band_colours(svg: str) -> list[tuple[float, str]]:
    band = r'<rect x="([\d.]+)" y="23" width="[\d.]+" height="14" fill="(#[0-9a-f]{6})"'
    return [(float(x), fill) for x, fill in re.findall(band, svg)]


def test_the_state_timeline_shows_each_state_and_the_label_and_event_rows(trace):
    svg = str(states_svg(trace))
    ElementTree.fromstring(svg)
    bands = _band_colours(svg)  # the state row: one band per run, left to right
    assert [fill for _, fill in bands] == [state_color(s) for s in ("go_to_goal", "follow_wall", "stop")]
    assert bands[0][0] < bands[1][0] < bands[2][0]
    assert ">fw_direction<" in svg and ">at_goal<" in svg and "follow_wall: 1.00 to 2.00 s" in svg


def test_signals_are_plotted_by_name(trace):
    svg = str(signals_svg(trace, ["d_prog", "switches", "u_gtg", "no_such_signal"]))
    ElementTree.fromstring(f"<div>{svg}</div>")  # one chart per unit
    for label in ("d_prog", "switches", "u_gtg x", "u_gtg y"):
        assert f">{label}</text>" in svg
    assert signals_svg(trace, ["no_such_signal", "fw_direction"]) is None  # nothing with a line to draw
    old = _module("simiam_test_synthetic_sp", DATA / "traces/synthetic.py").load("week4_wander.json")
    assert "signals" not in old and ">v</text>" in str(signals_svg(old, ["v", "w"]))  # an old trace


def _hostile_trace():
    return SWITCHING.switching_trace(("go_to_goal", EVIL_STATE, "stop"))


def test_student_state_names_stay_text():
    svg = str(states_svg(_hostile_trace()))
    ElementTree.fromstring(svg)
    assert "<script>" not in svg and "&lt;script&gt;" in svg


def test_a_timeline_that_pastes_names_is_caught():
    wrong = _module("report_wrong_states", DATA / "report_wrong/states_unescaped.py")
    svg = str(wrong.states_svg(_hostile_trace()))
    assert "<script>" in svg
    with pytest.raises(ElementTree.ParseError):
        ElementTree.fromstring(svg)


def test_a_check_declares_the_plots_of_its_runs(trace):
    plots = ["trajectory", "states", "signals:d_prog", "no_such_plot", "signals:nothing"]
    assert len(declared_plots(plots, trace)) == 2
    result = {"week": 5, "score": 1.0, "max_score": 1.0, "status": "graded", "submission": "alice",
              "checks": [{"id": "week5.switching", "name": "switching", "kind": "scenario",
                          "status": "passed", "points": 1.0, "max_points": 1.0, "message": "",
                          "plots": plots, "details": {"traces": ["week5.switching"]}}]}
    html = render_report(result, {"week5.switching": trace}, replays="none")
    assert "Which controller ran when" in html and "d_prog (m)" in html and "trajectory" in html


def test_checks_may_declare_state_and_signal_plots_and_nothing_else():
    from grader.checks import Check

    Check("week5.x", "x", "scenario", 1.0, lambda ctx: None, plots=("trajectory", "states", "signals:d_prog"))
    with pytest.raises(ValueError, match="unknown plots"):
        Check("week5.x", "x", "scenario", 1.0, lambda ctx: None, plots=("state",))


# ---- issue 22 item 3: any finite value, however large ----------------------------------------------------
BIG = 1.7976931348623157e308  # the largest float


def _huge_trace():
    trace = SWITCHING.switching_trace()
    n = len(trace["steps"]["t"])
    trace["steps"]["u_gtg"] = [[1e308, -1e308]] * n
    trace["steps"]["d_prog"] = [BIG if k % 2 else -BIG for k in range(n)]
    trace["steps"]["switches"] = list(range(n))  # beside them, a small signal still drawn
    return trace, n


def test_plots_survive_any_finite_value_and_say_what_is_off_the_chart():
    trace, n = _huge_trace()
    svg = str(signals_svg(trace, ["d_prog", "u_gtg", "switches"]))
    ElementTree.fromstring(f"<div>{svg}</div>")  # d_prog (m), u_gtg's x and y, switches (count)
    assert f">{n} values off the chart (beyond ±1,000,000)" in svg  # d_prog's chart
    assert f">{2 * n} values off the chart (beyond ±1,000,000)" in svg  # u_gtg's
    assert "inf" not in svg and "e+" not in svg and re.search(r'<path d="M[^"]+" fill="none"', svg)
    assert ">switches</text>" in svg


def test_a_huge_heading_or_estimate_stays_off_the_other_plots():
    from grader.report.svg import heading_svg, trajectory_svg

    trace, n = _huge_trace()
    trace["steps"]["theta_g"] = [BIG] * n  # the student's own theta_g, drawn when no goal is known
    trace["steps"]["x_est"] = [1e308] * n
    for svg in (str(heading_svg({**trace, "goal": None})), str(trajectory_svg(trace))):
        ElementTree.fromstring(svg)
        assert "inf" not in svg and "e+" not in svg
        assert max(len(number) for number in re.findall(r"-?[\d.]+", svg)) < 12  # no 300-digit pixel


def test_the_axis_of_every_finite_value_overflows():
    wrong = _module("report_wrong_axis", DATA / "report_wrong/unbounded_axis.py")
    with pytest.raises(OverflowError):
        wrong.signals_svg(_huge_trace()[0], ["d_prog", "u_gtg"])


def test_a_count_and_metres_never_share_an_axis(trace):
    """"d_prog, switches (m)" drew a count of switches on a metres axis: one chart per unit, each titled
    with its own."""
    svg = str(signals_svg(trace, ["d_prog", "switches"]))
    charts = ElementTree.fromstring(f"<div>{svg}</div>").findall("{http://www.w3.org/2000/svg}svg")
    titles = [c.find("{http://www.w3.org/2000/svg}title").text for c in charts]
    assert titles == ["d_prog (m)", "switches (count)"]


def test_no_row_label_is_cut_and_the_legend_keeps_inside():
    """The state chart cut "obstacle_cleared" to "bstacle_cleared" (its label ran off the left edge) and
    the legend ran off the right one: the margin fits the longest label (at a generous width per
    character) and the legend wraps. The browser test (test_report_pages_browser.py) measures the same
    on the rendered page."""
    from grader.report.signal_plots import _CHAR

    trace = SWITCHING.switching_trace()
    n = len(trace["steps"]["t"])
    trace["signals"] = [*trace["signals"], {"name": "obstacle_cleared", "kind": "flag"}]
    trace["steps"]["obstacle_cleared"] = [k % 7 == 0 for k in range(n)]
    names = ["go_to_goal", "avoid_obstacles", "follow_wall", "sliding_left", "sliding_right", "stop"]
    trace["steps"]["state"] = [names[k * len(names) // n] for k in range(n)]
    svg = ElementTree.fromstring(str(states_svg(trace)))
    width = float(svg.get("width"))
    texts = svg.findall("{http://www.w3.org/2000/svg}text")
    label = next(t for t in texts if t.text == "obstacle_cleared")
    assert float(label.get("x")) - _CHAR * len("obstacle_cleared") >= 0
    legend = [t for t in texts if t.text in names]
    assert {t.text for t in legend} == set(names)
    assert all(float(t.get("x")) + _CHAR * len(t.text) <= width for t in legend)
