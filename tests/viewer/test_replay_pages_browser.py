"""The replay of every week at 1024 and 1280 px in headless Chromium, measured as a person sees it: the
legend never covers the scale bar, no plot title is cut, nothing needs sideways scrolling; week 7's sigma
(two coefficients) is plotted, not drawn as an arrow out of the arena; and every state has the colour
the report gives it.

One short run of the course's solution per week, written once for the module."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from browser import chromium_context, solution_trace

from grader.report.signal_plots import state_color
from simiam.viewer.replay import write_replay

pytestmark = pytest.mark.browser
WIDTHS = (1024, 1280)
ASSIGNMENTS = Path(__file__).resolve().parents[2] / "assignments"
# the colour words a handout README may use for what the replay draws, and the colours they name
COLOUR_WORDS = {"red": "#d1242f", "green": "#1a7f37", "orange": "#b35900", "purple": "#7a3db8",
                "teal": "#0f8b8d", "pink": "#c2185b", "brown": "#5d4037", "black": "#111", "blue": "#1f4fd1"}
# "`u_ao` (the red arrow", "your `u_ao` (a green arrow", "`ir_distances_wf` (black crosses)"
SAYS_COLOUR = re.compile(r"`(\w+)` \((?:the |an? )?(\w+) (?:arrow|crosses|cross|line)")
# week 5's full 60 s (it stops at its goal after ~9 s); week 7 slides along the wall (sigma gets values)
# after ~20 s; 12 s shows the rest
SECONDS = {5: 60.0, 7: 30.0}

MEASURE = """() => {
  const widest = () => {  // the widest row label of the state timeline, measured here in the page's font
    const g = document.createElement('canvas').getContext('2d'); g.font = '10px system-ui, sans-serif';
    const rows = ['state', ...window.simiam.signalRows()];
    return Math.max(...rows.map(r => g.measureText(r).width));
  };
  const s = window.simiam.state(), [cl, ct] = s.canvasRect, legend = document.getElementById('legend');
  const l = legend.getBoundingClientRect(), stage = document.getElementById('stage').getBoundingClientRect();
  const [bx, by, bw, bh] = s.scaleBar;
  const bar = {left: cl + bx, top: ct + by, right: cl + bx + bw, bottom: ct + by + bh};
  const meets = Math.min(l.right, bar.right) > Math.max(l.left, bar.left) &&
                Math.min(l.bottom, bar.bottom) > Math.max(l.top, bar.top);
  const cut = [...document.querySelectorAll('.plot h2')].filter(h => h.scrollWidth > h.clientWidth + 1)
                .map(h => h.textContent);
  return {meets, cut, scroll: [document.documentElement.scrollWidth, innerWidth],
          legendInStage: l.left >= stage.left && l.right <= stage.right + 1 && l.bottom <= stage.bottom + 1,
          titles: [...document.querySelectorAll('.plot h2')].map(h => h.textContent),
          overlays: window.simiam.overlays().map(o => o.name), plotEnd: s.plotEnd, tEnd: s.tEnd,
          margins: s.labelMargins, widest: widest()};
}"""


@pytest.fixture(scope="module")
def replays(tmp_path_factory) -> dict[int, tuple[str, dict]]:
    out = tmp_path_factory.mktemp("replays")
    pages = {}
    for week in range(1, 8):
        trace = solution_trace(week, SECONDS.get(week, 12.0))
        pages[week] = (write_replay(trace, out / f"week{week}.html").resolve().as_uri(), trace)
    return pages


@pytest.mark.parametrize("width", WIDTHS)
def test_every_weeks_replay_reads_whole(replays: dict, width: int, tmp_path) -> None:
    seen, colours = {}, {}
    for context in chromium_context({"width": width, "height": 760}):
        page = context.new_page()
        for week, (uri, trace) in replays.items():
            page.goto(uri)
            page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
            page.evaluate("window.simiam.home()")
            seen[week] = page.evaluate(MEASURE)
            names = sorted({s for s in trace["steps"]["state"] if s})
            colours[week] = {n: page.evaluate("(n) => window.simiam.stateColor(n)", n) for n in names}
            page.screenshot(path=str(tmp_path / f"replay-week{week}-{width}.png"))
    assert {w: m for w, m in seen.items() if m["meets"]} == {}  # the legend wrapped over the scale bar
    assert {w: m["cut"] for w, m in seen.items() if m["cut"]} == {}
    assert {w: m["scroll"] for w, m in seen.items() if m["scroll"][0] > m["scroll"][1]} == {}
    assert all(m["legendInStage"] for m in seen.values())
    # the timeline's row labels fit their margin, measured from the labels (it was a fixed 92 px)
    assert max(seen[7]["margins"]) >= seen[7]["widest"] + 4
    # a 60 s run that stopped at its goal after ~9 s: the plots end soon after, not at 60 s
    assert seen[5]["tEnd"] > 59 and seen[5]["plotEnd"] < 15
    assert any(seen[w]["plotEnd"] == seen[w]["tEnd"] for w in (1, 3, 7))  # a run that moves to the end
    # week 7's sigmas: two coefficients each, plotted over time, not arrows from the robot
    assert not {"sigma_left", "sigma_right"} & set(seen[7]["overlays"]) and "u_gtg" in seen[7]["overlays"]
    assert any("sigma_left" in title and "coefficients" in title for title in seen[7]["titles"])
    # the report's colour of every state, on the replay's timeline
    assert all(colours[w] for w in (5, 6, 7))
    assert {w: c for w, c in colours.items() if c != {n: state_color(n) for n in c}} == {}


def test_the_handouts_name_the_colours_the_replay_draws(replays: dict) -> None:
    """The week-5 README called u_ao "the red arrow" while the replay draws it green: every colour a
    handout README gives a drawn signal is the colour its week's replay gives it."""
    drawn, said = {}, []
    for context in chromium_context({"width": 1024, "height": 760}):
        page = context.new_page()
        for week, (uri, _) in replays.items():
            page.goto(uri)
            page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
            drawn[week] = {o["name"]: o["color"] for o in page.evaluate("window.simiam.overlays()")}
    for week in drawn:
        text = " ".join((ASSIGNMENTS / f"week{week}" / "README.md").read_text(encoding="utf-8").split())
        for name, word in SAYS_COLOUR.findall(text):
            name = "ir_points_wf" if name == "ir_distances_wf" else name  # the signal its points come from
            said.append((week, name, word, drawn[week].get(name)))
    assert {(4, "u_ao"), (5, "u_ao"), (4, "ir_points_wf")} <= {(w, n) for w, n, _, _ in said}
    assert [s for s in said if COLOUR_WORDS.get(s[2]) != s[3]] == []
