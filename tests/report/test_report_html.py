"""The grader's HTML report as text: summary, checks table, details, escaping, plots and embedded replays."""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path
from xml.etree import ElementTree

import pytest

from grader.report import render_report, svg, write_report
from grader.report.html import format_metric

WRONG = Path(__file__).resolve().parents[1] / "data" / "report_wrong"


def _wrong():
    spec = importlib.util.spec_from_file_location("simiam_report_wrong", WRONG / "unescaped.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def student_markup_is_inert(html: str) -> bool:
    """No student-supplied tag survives as markup (the fixture's EVIL text appears only escaped)."""
    return "<script>window.pwned" not in html and "<img src=x" not in html and \
        "&lt;script&gt;window.pwned" in html


def svg_elements(html: str) -> list[ElementTree.Element]:
    """Every inline <svg> parsed as XML (a malformed plot raises)."""
    return [ElementTree.fromstring(m) for m in re.findall(r"<svg\b.*?</svg>", html, flags=re.S)]


def test_summary_and_checks_table(week3_result):
    result, traces = week3_result
    html = render_report(result, traces, replays="none")
    for text in ("Week 3 feedback", "4.5", "/ 10", "1234", "0.1.0+abcdef0123456789", "bwrap",
                 "hidden variants", "1 passed, 2 failed, 1 error"):
        assert text in html, text
    rows = re.findall(r"<tr class=\"(passed|failed|error|timeout)\">", html)
    assert rows == ["failed", "failed", "error", "passed"]  # failures first, in the declared order
    assert 'href="#check-week3.pid.integral"' in html and 'id="check-week3.pid.integral"' in html


def test_property_counterexample_and_replay_command(week3_result):
    result, traces = week3_result
    html = render_report(result, traces, replays="none")
    section = html.split('id="check-week3.pid.integral"', 1)[1].split("</article>", 1)[0]
    assert "Counterexample" in section and "<th>e_k</th>" in section and "<code>0.033</code>" in section
    assert "grade week3 ./alice --check week3.pid.integral --case &#39;e_k=0.5,dt=0.033&#39;" in section


def test_scenario_metrics_and_plots(week3_result):
    result, traces = week3_result
    html = render_report(result, traces, replays="none")
    section = html.split('id="check-week3.go_to_goal.reaches_goals"', 1)[1].split("</article>", 1)[0]
    for text in ("time to goal", "11.2 s", "final distance", "0.048 m", "minimum clearance", "settle time",
                 "1.32 s", "overshoot", "4.0 %", "never", "it collided at t = 6.73 s"):
        assert text in section, text
    plots = svg_elements(section)
    assert len(plots) == 4  # trajectory and heading for each of the two runs
    assert section.count("collision at t = 6.73 s") == 1  # only the second run crashed
    assert "settled 1.32 s" in section and "settled 0.45 s" in section


def test_student_text_is_escaped(week3_result):
    result, traces = week3_result
    result["submission"] = "<b>alice</b>"
    html = render_report(result, traces, replays="none")
    assert student_markup_is_inert(html)
    assert "&lt;b&gt;alice&lt;/b&gt;" in html
    assert not student_markup_is_inert(_wrong().render_unescaped(result, traces))


def test_inline_replays_are_sandboxed_iframes(week3_result):
    result, traces = week3_result
    html = render_report(result, traces)
    frames = re.findall(r"<iframe [^>]*srcdoc=\"([^\"]*)\"", html)
    assert len(frames) == 2
    assert all(f.startswith("&lt;!doctype html&gt;") for f in frames)
    assert html.count('sandbox="allow-scripts"') == 2  # no same-origin: a replay cannot touch the report
    print(f"week-3 sample report with two inline replays: {len(html.encode())} bytes")


def test_long_runs_are_thinned_in_the_report(synthetic, week3_result):
    result, _ = week3_result
    long_run = synthetic.make_trace(week=4, seconds=60.0, stop_on_collision=False)
    traces = {"week3.go_to_goal.reaches_goals": long_run, "week3.go_to_goal.reaches_goals#2": long_run}
    html = render_report(result, traces)
    size = len(html.encode())
    print(f"report with two 60 s replays inline: {size} bytes")
    assert "1 step in 2 shown" in html
    assert size < 1_000_000


def test_write_report_files_mode_links_replays(week3_result, tmp_path):
    result, traces = week3_result
    path = write_report(result, traces, tmp_path / "out" / "week3.html", replays="files")
    html = path.read_text()
    assert "srcdoc" not in html
    links = re.findall(r'href="(week3-replays/[^"]+)"', html)
    assert len(links) == 2 and all((path.parent / link).is_file() for link in links)


def test_invalid_submission_and_broken_traces(week3_result):
    result, traces = week3_result
    invalid = {"week": 3, "score": 0, "max_score": 10, "status": "invalid", "seed": 1, "grader_version": "x",
               "message": "go_to_goal.py line 3: invalid syntax", "checks": []}
    html = render_report(invalid, {})
    assert "go_to_goal.py line 3: invalid syntax" in html and "badge invalid" in html
    empty = {"format": "simiam-trace/1", "week": 3, "robot": {}, "steps": {"t": []}, "world": {}}
    html = render_report(result, {"week3.go_to_goal.reaches_goals": empty})
    assert "ended before the robot's first step" in html


def test_metric_formatting():
    assert format_metric("overshoot", 0.123) == "12.3 %"
    assert format_metric("settle_time", None) == "never"
    assert format_metric("reached", False) == "no"
    assert format_metric("final_distance", 0.04812345) == "0.048 m"
    assert format_metric("goal", [1.0, -0.5]) == "(1, -0.5)"


def test_svg_helpers_escape_and_parse():
    evil = "<script>x</script>"
    hist = svg.histogram_svg([0, 2.5, 10, 10, 7.4], max_score=10, title=evil)
    bars = svg.pass_rate_svg([(evil, 0.25), ("week3.pid.p", 1.0)])
    for picture in (hist, bars):
        ElementTree.fromstring(str(picture))
        assert "<script>" not in picture
    counts = [int(t) for t in re.findall(r"<title>[^<]*: (\d+)</title>", str(hist))]
    assert counts == [1, 0, 1, 0, 0, 0, 0, 1, 0, 2]  # 10 lands in the top bin, not an eleventh one
    # the count over the tallest bar sits a full line (font 11) below the title, not on it
    title_y = float(re.search(r'<text x="[\d.]+" y="([\d.]+)" font-weight="600">', str(hist)).group(1))
    count_y = min(float(y) for y in re.findall(r'<text x="[\d.]+" y="([\d.]+)" text-anchor="middle">\d+<',
                                               str(hist)))
    assert count_y - 11 >= title_y
    last_tick = re.findall(r'<text x="([\d.]+)" y="[\d.]+" text-anchor="middle" fill="#555">10.0<', str(hist))
    assert float(last_tick[0]) + 4 * 6 / 2 <= 520   # "10.0" centred on the axis end stays inside the picture
    assert "25%" in bars and "100%" in bars


@pytest.mark.parametrize("goal", [(1.0, 1.0), None])
def test_heading_plot_band_follows_the_reference(synthetic, goal):
    trace = synthetic.load("week3_goal.json")
    trace["goal"] = None  # then the plot falls back to the controller's own theta_g column
    picture = str(svg.heading_svg(trace, goal=goal, settle_time=1.0))
    ElementTree.fromstring(picture)
    assert ("true position to goal" in picture) == (goal is not None)
    assert picture.count('fill="rgba(209,36,47,0.12)"') >= 1  # the settle band is drawn


def test_a_check_that_measured_another_checks_run_plots_it(week3_result):
    result, traces = week3_result
    result["checks"].append(
        {"id": "week3.pid.settle_time", "name": "settle time", "kind": "scenario", "visibility": "visible",
         "points": 1.0, "max_points": 1.0, "status": "passed", "message": "settled after 1.32 s",
         "details": {"goal": [1.0, 1.0], "settle_time": 1.32, "overshoot": 0.04}})
    html = render_report(result, traces)
    section = html.split('id="check-week3.pid.settle_time"', 1)[1].split("</article>", 1)[0]
    assert 'href="#run-week3.go_to_goal.reaches_goals"' in section  # its replay is not embedded twice
    assert "srcdoc" not in section and len(svg_elements(section)) == 2 and "settled 1.32 s" in section
    result["checks"][-1]["details"]["goal"] = [5.0, 5.0]  # no run went there: nothing to plot
    section = render_report(result, traces).split('id="check-week3.pid.settle_time"', 1)[1]
    assert not svg_elements(section.split("</article>", 1)[0])


def test_a_run_two_checks_list_is_embedded_once_and_ids_stay_unique(week3_result):
    result, traces = week3_result
    result["checks"].append(
        {"id": "week3.pid.overshoot", "name": "overshoot", "kind": "scenario", "points": 0.0,
         "max_points": 1.0, "status": "failed", "message": "overshoot 30 %",
         "details": {"goal": [1.0, 1.0], "overshoot": 0.3, "traces": ["week3.go_to_goal.reaches_goals"]}})
    html = render_report(result, traces)
    assert html.count("<iframe") == 2                      # the two runs, not three
    ids = re.findall(r' id="([^"]+)"', html)
    assert len(ids) == len(set(ids))
    section = html.split('id="check-week3.pid.overshoot"', 1)[1].split("</article>", 1)[0]
    assert 'href="#run-week3.go_to_goal.reaches_goals"' in section and len(svg_elements(section)) == 2


def test_unlabelled_runs_take_their_trace_labels(week3_result):
    result, traces = week3_result
    for run in result["checks"][2]["details"]["runs"]:
        del run["goal"]
    html = render_report(result, traces, replays="none")
    table = html.split('<table class="metrics">', 1)[1].split("</table>", 1)[0]
    assert "<th>run</th>" in table and "<td>goal (1, 1)</td>" in table and "<td>goal (2, -0.3)</td>" in table


def test_file_problems_notices_and_printed_output(week3_result):
    result, traces = week3_result
    result.update({"problems": {"go_to_goal.py": ["go_to_goal.py:12: <b>invalid syntax</b>"],
                                "quickbot.py": ["get_ir_distances is missing"]},
                   "notices": ["qb_supervisor.py:3: changed outside the code blocks (not used)"],
                   "student_output": "hello from the student <script>window.pwned = 3</script>",
                   "hidden_checks_not_run": 2, "isolation_note": "bubblewrap sandbox"})
    html = render_report(result, traces, replays="none")
    assert "<li>go_to_goal.py:12: &lt;b&gt;invalid syntax&lt;/b&gt;</li>" in html
    assert "<li>quickbot.py: get_ir_distances is missing</li>" in html
    assert "changed outside the code blocks" in html and "bubblewrap sandbox" in html
    assert "4 visible checks ran here; 2 hidden checks (other goals, drawn per seed) run at official" in html
    assert "hello from the student &lt;script&gt;" in html and "<script>window.pwned = 3" not in html


def test_a_go_to_angle_run_plots_theta_against_theta_d(synthetic):
    trace = synthetic.load("week3_goal.json")
    trace.update(week=2, goal=None)
    trace["steps"]["theta_g"] = [None] * len(trace["steps"]["t"])
    result = {"week": 2, "score": 0.0, "max_score": 1.5, "status": "graded", "seed": 1, "checks": [
        {"id": "week2.go_to_angle.reaches_theta_d", "name": "go-to-angle", "kind": "scenario", "points": 0.0,
         "max_points": 1.5, "status": "failed", "message": "the true heading ended 2.92 rad away",
         "details": {"runs": [{"theta_d": 0.785, "heading_error": 2.92}],
                     "traces": ["week2.go_to_angle.reaches_theta_d"]}}]}
    html = render_report(result, {"week2.go_to_angle.reaches_theta_d": trace}, replays="none")
    titles = [el.findtext("{http://www.w3.org/2000/svg}title") for el in svg_elements(html)]
    assert "Heading θ against θ_d" in titles and "θ should reach θ_d and stay there" in html
    plot = html.split("Heading θ against θ_d", 1)[1].split("</svg>", 1)[0]
    lines = re.findall(r'<path d="M([^"]+)"', plot)
    assert len(lines) == 3                             # θ (true), θ_d, θ (estimate)
    assert len({pt.split()[-1] for pt in lines[1].split(" L")}) == 1 and len(lines[0].split(" L")) > 10


def test_failures_come_first_and_passed_checks_are_collapsed(week3_result):
    result, traces = week3_result
    result["checks"][2]["status"] = "passed"  # a passed check with runs and plots: collapsed all the same
    html = render_report(result, traces, replays="none")
    articles = re.findall(r'<article class="check (\w+)" id="check-([^"]+)">\s*'
                          r'<details class="check-body"( open)?>', html)
    assert [(status, cid) for status, cid, _ in articles] == [
        ("failed", "week3.pid.integral"), ("error", "week3.ensure_w.keeps_w"),
        ("passed", "week3.theta_g.quadrants"), ("passed", "week3.go_to_goal.reaches_goals")]
    assert [bool(is_open) for _, _, is_open in articles] == [True, True, False, False]
    rows = re.findall(r"<tr class=\"(passed|failed|error|timeout)\">", html)
    assert rows == ["failed", "error", "passed", "passed"]


def test_a_run_that_never_started_gets_one_line_not_an_empty_plot(week3_result):
    result, traces = week3_result
    crash = traces["week3.go_to_goal.reaches_goals#2"]
    # what a run keeps when the student's code raised at the first step: row 0, the start pose, only
    crash["steps"] = {name: column[:1] for name, column in crash["steps"].items()}
    crash["collision"] = None
    html = render_report(result, traces)
    section = html.split('id="check-week3.go_to_goal.reaches_goals"', 1)[1].split("</article>", 1)[0]
    assert len(svg_elements(section)) == 2 and section.count("<iframe") == 1  # the first run only
    assert "Run goal (2, -0.3): ended before the robot's first step" in section


def test_the_trajectory_legend_is_under_the_map_clear_of_the_walls(synthetic):
    trace = synthetic.load("week3_goal.json")
    size = 360
    picture = ElementTree.fromstring(str(svg.trajectory_svg(trace, size=size)))
    ns = "{http://www.w3.org/2000/svg}"
    walls = [float(v) for poly in picture.iter(ns + "polygon")
             for point in poly.get("points").split() for v in point.split(",")[1:]]
    assert walls and max(walls) <= size  # every obstacle is drawn on the map
    legend = next(g for g in picture.iter(ns + "g") if "true path" in "".join(g.itertext()))
    legend_top = float(re.search(r"translate\([\d.]+ ([\d.]+)\)", legend.get("transform"))[1]) - 11  # font 11
    assert legend_top >= size and float(picture.get("height")) >= legend_top + 11


@pytest.mark.parametrize("where", ["right", "left", "top"])
def test_the_collision_label_stays_on_the_map(synthetic, where):
    trace = synthetic.load("week3_crash.json")
    xs = [x for poly in trace["world"]["obstacles"] for x, _ in poly]
    ys = [y for poly in trace["world"]["obstacles"] for _, y in poly]
    pose = {"right": [max(xs) - 0.05, 0.0], "left": [min(xs) + 0.05, 0.0],
            "top": [0.0, max(ys) - 0.02]}[where]
    trace["collision"]["pose"] = pose + [0.0]
    size = 360
    picture = ElementTree.fromstring(str(svg.trajectory_svg(trace, size=size)))
    texts = picture.iter("{http://www.w3.org/2000/svg}text")
    label = next(t for t in texts if "collision at" in (t.text or ""))
    x, y, width = float(label.get("x")), float(label.get("y")), 6.5 * len(label.text)  # font 11, bold
    left = x - width if label.get("text-anchor") == "end" else x
    assert 0 <= left and left + width <= size and 11 <= y <= size


@pytest.mark.parametrize("declared,classes", [
    (["trajectory"], ["trajectory", "trajectory"]),
    (["trajectory", "heading"], ["trajectory", "heading", "trajectory", "heading"]),
    (["heading"], ["heading", "heading"]),
    ([], []),
])
def test_the_report_draws_what_the_check_declared(week3_result, declared, classes):
    """The runs of a goal check get the plots its declaration names (Check.plots, in the result), not
    what the week number or the run's data would suggest."""
    result, traces = week3_result
    result["checks"][2]["plots"] = declared
    html = render_report(result, traces, replays="none")
    section = html.split('id="check-week3.go_to_goal.reaches_goals"', 1)[1].split("</article>", 1)[0]
    drawn = ["trajectory" if "trajectory" in (el.get("class") or "") else "heading"
             for el in svg_elements(section)]
    assert drawn == classes


def test_a_scenario_result_carries_its_checks_plots() -> None:
    from grader.checks import Check, Context, Outcome, checks_for_week, run_check

    goal = {c.id: c.plots for c in checks_for_week(3) if c.kind == "scenario"}
    assert set(goal.values()) == {("trajectory", "heading")}
    assert {c.plots for c in checks_for_week(2) if c.kind == "scenario"} == {("trajectory", "angle")}
    ctx = Context(week=3, seed=1, session=None)
    scenario = Check("week3.x.y", "x", "scenario", 1.0, lambda ctx: Outcome(1.0), plots=("heading",))
    prop = Check("week3.x.z", "x", "property", 1.0, lambda ctx: Outcome(1.0), plots=("heading",))
    assert run_check(scenario, ctx, {}).to_json()["plots"] == ["heading"]
    assert "plots" not in run_check(prop, ctx, {}).to_json()
    with pytest.raises(ValueError, match="unknown plots"):
        Check("week3.x.w", "x", "scenario", 1.0, lambda ctx: Outcome(1.0), plots=("radar",))


def test_the_cached_template_environment_still_escapes_every_report(week3_result):
    """The report's environment and the replay's template are built once per process (a batch renders
    hundreds of reports): a second report with other hostile text is escaped as the first was, and the
    environment is the same object (built once, not per report)."""
    from grader.report import html as report_html
    from simiam.viewer import replay

    result, traces = week3_result
    first = render_report(result, traces)
    assert report_html._env() is report_html._env() and replay._template() is replay._template()
    result = {**result, "submission": "<img src=x onerror=alert(1)>"}
    traces = {k: {**t, "meta": {**(t.get("meta") or {}), "check_label": "</script><script>window.pwned=1"}}
              for k, t in traces.items()}
    second = render_report(result, traces)
    assert student_markup_is_inert(first) and student_markup_is_inert(second)
    assert "&lt;img src=x onerror=alert(1)&gt;" in second and "<img src=x" not in second
    assert "</script><script>window.pwned=1" not in second


@pytest.mark.parametrize("value, text", [(1.0, "1"), (10.0, "10"), (2.5, "2.5"), (-2.5, "-2.5"),
                                         (1.239, "1.24"), (3.14159, "3.14"), (0.0, "0"), (-0.0, "0"),
                                         (-0.004, "0"), (0.004, "0"), (-0.01, "-0.01"), (120.10, "120.1"),
                                         (7, "7")])
def test_plot_coordinates_have_at_most_two_decimals_and_never_minus_zero(value, text):
    assert svg._n(value) == text
