"""Issue 24 made the grading process's metrics and report cheaper without changing a figure or a pixel:

- min_clearance measures only the steps whose cheap lower bound can beat the smallest gap (grader/scenarios
  and grader/clearance.pose_bounds): bit for bit the figure of the version that measured every step (kept in
  tests/data/before_issue24), on random runs through every kind of world (square, turned, mirrored, odd
  polygons, runs into obstacles), and on every run of the solutions and the stubs of weeks 4-7 (with
  SIMIAM_SAME_AFTER_ISSUE24=full, of the kept wrong versions too); a kept wrong bound (the plate's box not
  turned with the robot) is caught;
- the laps' median distance to the obstacle skips edges already farther: the same figure;
- the report (its charts, top views and embedded replays) byte for byte the one the old plots and replay
  packing wrote, for each of those gradings.
"""

from __future__ import annotations

import importlib.util
import math
import os
import random
import sys
from pathlib import Path
from types import ModuleType

import pytest
from mistakes import DATA, build, read_mistake

import grader.laps as laps
import grader.report.html as html
import grader.scenarios as scenarios
from grader import clearance
from grader.checks import week6
from grader.checks.week4 import _variant
from grader.checks.week7 import turned
from grader.grading import grade_submission
from simiam.course.weeks import get_week
from simiam.trace import Trace
from simiam.world import World, load_world

ROOT = Path(__file__).resolve().parents[2]
BEFORE = DATA / "before_issue24"
SPEC = get_week(4).spec


def _load(name: str, path: Path, aliases: dict[str, ModuleType] | None = None) -> ModuleType:
    """A kept file as a module of its own name; `aliases` stand in for the modules it imports while it
    loads (the old signal plots draw with the old svg)."""
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    saved = {k: sys.modules.get(k) for k in [*(aliases or {}), name]}
    sys.modules.update({**(aliases or {}), name: module})
    try:
        spec.loader.exec_module(module)
    finally:
        for k, v in saved.items():
            if v is None:
                sys.modules.pop(k, None)
            else:
                sys.modules[k] = v
    return module


OLD_CLEARANCE = _load("before_issue24_clearance", BEFORE / "clearance.py")
OLD_MIN = _load("before_issue24_min_clearance", BEFORE / "min_clearance.py", {"clearance": OLD_CLEARANCE})
OLD_LAPS = _load("before_issue24_laps", BEFORE / "laps.py")
OLD_SVG = _load("before_issue24_svg", BEFORE / "svg.py")
OLD_PLOTS = _load("before_issue24_signal_plots", BEFORE / "signal_plots.py", {"grader.report.svg": OLD_SVG})
OLD_REPLAY = _load("before_issue24_replay", BEFORE / "replay.py")


def _same_float(a: float | None, b: float | None) -> bool:
    if a is None or b is None:
        return a is b
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b) or (a != a and b != b)


def _worlds() -> list[World]:
    """Square worlds, the hidden checks' turned and mirrored ones, and odd polygons at odd angles (a
    triangle, a thin sliver, a non-convex star, a degenerate edge), with the arena walls."""
    worlds = [load_world(name) for name in ("week3", "week4", "week6", "final")]
    worlds += [_variant(load_world("week4"), turn, 8, mirror)
               for turn, mirror in ((1, False), (3, True), (5, True))]
    worlds += [turned(load_world("final"), (1.0, 1.0), turn, 8)[0] for turn in (1, 4, 7)]
    star = [(0.4 * math.cos(k * math.pi / 5) * (1 if k % 2 else 0.4) + 0.3,
             0.4 * math.sin(k * math.pi / 5) * (1 if k % 2 else 0.4) - 0.2) for k in range(10)]
    odd = [[(-0.6, 0.3), (-0.2, 0.9), (-0.9, 0.7)], [(0.5, 0.5), (0.52, 0.51), (1.1, 1.2), (1.08, 1.21)],
           star, [(-0.7, -0.7), (-0.7, -0.7), (-0.4, -0.9), (-0.5, -0.5)]]
    worlds.append(World("odd polygons", [*odd, *load_world("week3").obstacles]))
    return worlds


def _wander(rng: random.Random, world: World, steps: int) -> Trace:
    """A run as the simulator records one: up to 7.5 mm and 0.25 rad a step, from near an obstacle, turning
    back at the arena's edge; it may drive through obstacles (a gap of 0 for a while)."""
    corner = rng.choice([p for poly in world.obstacles for p in poly])
    x, y = corner[0] + rng.uniform(-0.3, 0.3), corner[1] + rng.uniform(-0.3, 0.3)
    th = rng.uniform(-math.pi, math.pi)
    xs, ys, ths = [], [], []
    for _ in range(steps):
        xs.append(x)
        ys.append(y)
        ths.append(th)
        th += rng.uniform(-0.25, 0.25)
        step = rng.uniform(0.0, 0.0075)
        x, y = x + step * math.cos(th), y + step * math.sin(th)
        if abs(x) > 1.6 or abs(y) > 1.6:
            th += math.pi
    return Trace(week=4, dt=0.033, world={}, robot={}, start=[xs[0], ys[0], ths[0]],
                 steps={"x": xs, "y": ys, "theta": ths})


def _random_runs(seed: str) -> list[tuple[Trace, World, int]]:
    rng = random.Random(seed)
    runs = []
    for world in _worlds():
        for _ in range(6):
            steps, every = rng.choice((1, 2, 40, 300, 900)), rng.choice((1, 1, 1, 3))
            runs.append((_wander(rng, world, steps), world, every))
    return runs


def test_min_clearance_is_the_every_step_figure_on_random_runs_through_every_kind_of_world() -> None:
    touched = near = 0
    for trace, world, every in _random_runs("issue 24"):
        ours = scenarios.min_clearance(trace, world, SPEC, every)
        theirs = OLD_MIN.min_clearance(trace, world, SPEC, every)
        assert _same_float(ours, theirs), (world.name, every, ours, theirs)
        touched += ours == 0.0
        near += 0.0 < ours < 0.05
    assert touched > 5 and near > 5  # runs into obstacles and runs close by, where culling decides


def test_a_run_of_poses_that_are_not_numbers_has_the_same_figure() -> None:
    world = load_world("week4")
    xs, ys, ths = [0.0, math.nan, 0.1, 0.2], [0.0, 0.0, math.nan, 0.0], [0.0, 0.0, 0.0, math.nan]
    trace = Trace(week=4, dt=0.033, world={}, robot={}, start=[0, 0, 0],
                  steps={"x": xs, "y": ys, "theta": ths})
    assert _same_float(scenarios.min_clearance(trace, world, SPEC), OLD_MIN.min_clearance(trace, world, SPEC))
    nothing = Trace(week=4, dt=0.033, world={}, robot={}, start=[0, 0, 0],
                    steps={"x": [math.nan], "y": [0.0], "theta": [0.0]})
    ours = scenarios.min_clearance(nothing, world, SPEC)
    assert ours == OLD_MIN.min_clearance(nothing, world, SPEC) == math.inf


def test_every_bound_is_below_the_gap_it_bounds() -> None:
    """pose_bounds never exceeds the gap measured at that pose (the culling's one premise), and is close to
    it: the plate's box, not a circle around it."""
    rng = random.Random("bounds")
    slack_used = []
    for trace, world, _ in _random_runs("bounds")[::3]:
        shapes = [clearance.Shape(p) for p in world.obstacles]
        s = trace.steps
        poses = list(zip(s["x"], s["y"], s["theta"], strict=True))
        bounds = clearance.pose_bounds(SPEC.base_plate, poses, shapes)
        for pose, bound in rng.sample(list(zip(poses, bounds, strict=True)), min(40, len(poses))):
            body = clearance.Shape(scenarios.ref.placed(pose, SPEC.base_plate))
            gap = min(clearance.distance(body, shape) for shape in shapes)
            assert bound <= gap, (world.name, pose, bound, gap)
            slack_used.append(gap - max(bound, 0.0))
    assert sorted(slack_used)[len(slack_used) // 2] < 0.02  # the median bound is within 2 cm of its gap


def test_the_comparison_catches_a_bound_that_forgets_the_robot_turns(monkeypatch) -> None:
    wrong = _load("clearance_wrong_unturned", DATA / "clearance_wrong" / "unturned_bounds.py")
    monkeypatch.setattr(clearance, "pose_bounds", wrong.pose_bounds)
    differ = sum(not _same_float(scenarios.min_clearance(t, w, SPEC, e), OLD_MIN.min_clearance(t, w, SPEC, e))
                 for t, w, e in _random_runs("issue 24"))
    assert differ > 0  # (7 of the 66 runs: where a turned plate reached nearer than its unturned box)


def test_the_laps_median_distance_is_the_every_edge_one() -> None:
    """grader.laps.median_distance skips edges already farther than the nearest: the same median, and
    each point's distance the same as distance_to's, on random runs through every kind of world."""
    points = 0
    for trace, world, every in _random_runs("laps"):
        xs, ys = trace.steps["x"], trace.steps["y"]
        obstacles = [list(p) for p in world.obstacles]
        if len(xs) > 2:
            ours = laps.median_distance(xs, ys, obstacles, every)
            assert _same_float(ours, OLD_LAPS.median_distance(xs, ys, obstacles, every)), world.name
        edges = [seg for poly in obstacles for seg in clearance.Shape(poly).segments]
        for x, y in list(zip(xs, ys, strict=True))[::7]:
            assert _same_float(clearance.nearest_edge((x, y), edges), OLD_LAPS.distance_to((x, y), obstacles))
            points += 1
    assert points > 1000


# ---- every run and report of the kept versions -----------------------------------------------------------

# The suite compares the solutions and the stubs (their hidden runs hold every kind of world, turned ones
# too); SIMIAM_SAME_AFTER_ISSUE24=full adds the 48 kept versions (about 100 s more on one core).
FULL = os.environ.get("SIMIAM_SAME_AFTER_ISSUE24") == "full"


def _versions() -> list[tuple[str, int]]:
    out = [(f"{kind}/week{week}", week) for kind in ("solutions", "assignments") for week in (4, 5, 6, 7)]
    return out + [(p.stem, read_mistake(p).week) for p in sorted((DATA / "wrong").glob("*.patch"))
                  if FULL and read_mistake(p).week >= 4]


def _old_report(result: dict, traces: dict) -> str:
    """The report as the old plots and replay packing drew it (html.py itself is unchanged)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(html, "svg", OLD_SVG)
        mp.setattr(html, "declared_plots", OLD_PLOTS.declared_plots)
        mp.setitem(sys.modules, "simiam.viewer.replay", OLD_REPLAY)
        return html.render_report(result, traces)


@pytest.fixture(scope="module")
def graded(tmp_path_factory) -> dict:
    """Each kept version of weeks 4-7 graded once (hidden checks included, but for week 6's wrong
    versions, whose extra laps add minutes and no new kind of world), every min_clearance call compared with
    the old one on the spot, and so each of week 6's laps median distances: {"versions": {label:
    {"result", "traces", "clearances": [(ours, theirs)]}}, "medians": [(ours, theirs)]}."""
    tmp = tmp_path_factory.mktemp("issue24")
    measured: list[tuple[float | None, float | None]] = []
    real = scenarios.min_clearance

    def both(trace, world, spec, every=1):
        ours = real(trace, world, spec, every)
        measured.append((ours, OLD_MIN.min_clearance(trace, world, spec, every)))
        return ours

    def both_medians(xs, ys, obstacles, every=5):
        ours = laps.median_distance(xs, ys, obstacles, every)
        medians.append((ours, OLD_LAPS.median_distance(xs, ys, obstacles, every)))
        return ours

    medians: list[tuple[float, float]] = []
    out: dict[str, dict] = {}
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(scenarios, "min_clearance", both)
        mp.setattr(week6, "median_distance", both_medians)
        for label, week in _versions():
            folder = ROOT / label if "/" in label else build("wrong", label, tmp, week)
            measured.clear()
            traces: dict[str, dict] = {}
            hidden = "/" in label or week != 6
            result = grade_submission(week, folder, seed=2014, hidden=hidden, traces=traces)
            out[label] = {"result": result, "traces": traces, "clearances": list(measured)}
    return {"versions": out, "medians": medians}


@pytest.mark.slow
def test_every_run_of_the_kept_versions_has_the_every_step_clearance(graded) -> None:
    runs = 0
    for label, g in graded["versions"].items():
        assert g["result"]["status"] == "graded", label
        for ours, theirs in g["clearances"]:
            assert _same_float(ours, theirs), (label, ours, theirs)
            runs += 1
    assert runs > (150 if FULL else 25)  # every scenario run of every version, hidden turned worlds included
    medians = graded["medians"]
    assert len(medians) > (20 if FULL else 4), medians
    assert all(_same_float(ours, theirs) for ours, theirs in medians), medians


@pytest.mark.slow
def test_every_report_of_the_kept_versions_is_the_old_one_byte_for_byte(graded) -> None:
    for label, g in graded["versions"].items():
        ours = html.render_report(g["result"], g["traces"])
        assert ours == _old_report(g["result"], g["traces"]), label
    assert sum(len(g["traces"]) for g in graded["versions"].values()) > (150 if FULL else 25)
