"""The compact plots of a batch's student pages (grader.report.svg.compact_plots): a line keeps only the
points it needs to pass within half a pixel of every point it had, so the picture is the same at screen
resolution (a simplification that lets an arc drift, tests/data/report_wrong/local_simplify.py, is caught);
a straight or flat stretch is drawn by its ends; plots outside the block are drawn as before."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

from grader.report import svg

WRONG = Path(__file__).resolve().parents[1] / "data" / "report_wrong" / "local_simplify.py"


def farthest(points: list[tuple[float, float]], kept: list[tuple[float, float]]) -> float:
    """How far the line through `kept` (a subsequence of `points`) passes from the farthest point."""
    index = {id(p): k for k, p in enumerate(points)}
    ends = [index[id(p)] for p in kept]
    worst = 0.0
    for a, b in zip(ends, ends[1:], strict=False):
        (ax, ay), (bx, by) = points[a], points[b]
        dx, dy = bx - ax, by - ay
        length = math.hypot(dx, dy)
        for x, y in points[a + 1:b]:
            t = max(0.0, min(1.0, ((x - ax) * dx + (y - ay) * dy) / (length * length))) if length else 0.0
            worst = max(worst, math.hypot(x - ax - t * dx, y - ay - t * dy))
    return worst


def shapes() -> dict[str, list[tuple[float, float]]]:
    arc = [(200 + 150 * math.cos(a / 400), 200 + 150 * math.sin(a / 400)) for a in range(0, 1200, 4)]
    noise = [(k * 1.6, 100 + 30 * math.sin(k * 1.3) + (k % 7)) for k in range(250)]
    loop = [(100 + 40 * math.cos(a / 20), 100 + 40 * math.sin(a / 20)) for a in range(126)]
    loop.append((140.0, 100.0))                                 # back where it began
    return {"arc": arc, "noise": noise, "loop": loop}


def test_every_point_stays_within_half_a_pixel_of_the_simplified_line() -> None:
    for name, points in shapes().items():
        kept = svg._simplified(points)
        assert kept[0] is points[0] and kept[-1] is points[-1], name
        assert farthest(points, kept) <= 0.5 + 1e-9, name
    line = [(k * 2.0, 50.0 + 0.5 * k) for k in range(250)]
    assert svg._simplified(line) == [line[0], line[-1]]       # a straight stretch: its two ends


def test_the_check_catches_a_simplification_that_lets_an_arc_drift() -> None:
    spec = importlib.util.spec_from_file_location("local_simplify", WRONG)
    wrong = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(wrong)
    arc = shapes()["arc"]
    assert farthest(arc, wrong.simplified(arc)) > 5.0


def test_only_plots_made_inside_the_block_are_compact() -> None:
    chart = svg.Chart([svg.Series("v", [k * 0.033 for k in range(900)],
                                  [math.sin(k / 50) for k in range(900)])])
    before = chart.render()
    with svg.compact_plots():
        compact = chart.render()
    assert chart.render() == before and len(compact) < len(before) / 2
    assert all(len(n.split(".")[-1]) <= 1 for n in compact.split('d="M', 1)[1].split('"')[0]
               .replace("L", " ").split() if "." in n)                         # one decimal
