"""The pieces that keep the fast path exact: the plain transform's error bound, the culled loop's margins
(a decided answer holds for every placement within the slack), the raw values' rounding boundaries and
the near-parallel headings (simiam.physics.transform, segments, parallel; simiam.robot.ir_sensor)."""

from __future__ import annotations

import math
import random

import pytest

from simiam.course.weeks import spec_for_week
from simiam.physics.collision import plate_collides, plate_collides_exact
from simiam.physics.ir_ranging import cone_range, cone_range_exact
from simiam.physics.parallel import NearParallel
from simiam.physics.precheck import span
from simiam.physics.segments import ObstacleEdges, crossing, tolerance
from simiam.physics.transform import fast_error, transform_exact, transform_fast
from simiam.robot.ir_sensor import distance_to_raw, ir_voltage, mounted_cone, settled_raw
from simiam.world import load_world

SPEC = spec_for_week(4)
PLATE = list(SPEC.base_plate)
CONES = [mounted_cone(m, SPEC.ir_max_range, SPEC.ir_spread) for m in SPEC.ir_mounts]
REACH = max(math.hypot(px, py) for cone in CONES for px, py in cone)


def test_fast_error_bounds_the_plain_transform():
    rng = random.Random(31)
    worst, differ = 0.0, 0
    for _ in range(3000):
        scale = rng.choice([1.0, 10.0, 1000.0])
        pose = (rng.uniform(-scale, scale), rng.uniform(-scale, scale), rng.uniform(-50, 50))
        points = [(rng.uniform(-REACH, REACH) / 1.5, rng.uniform(-REACH, REACH) / 1.5) for _ in range(6)]
        fast = transform_fast(pose, points)
        exact = transform_exact(pose, points)
        bound = fast_error(REACH, max(abs(pose[0]), abs(pose[1])) + REACH)
        for f, e in zip(fast[0] + fast[1], exact[0] + exact[1], strict=True):
            worst = max(worst, abs(f - e) / bound)
            differ += f != e
    assert differ > 100  # the two placements do differ, in the last bits
    assert worst <= 1.0


def nudged(rng: random.Random, values: list[float], slack: float) -> list[float]:
    """Each value moved by a random whole number of its ulps, at most `slack` away."""
    out = []
    for v in values:
        steps = int(slack / math.ulp(v)) if v else 0
        out.append(v + rng.randint(-steps, steps) * math.ulp(v))
    return out


def near_contact(rng: random.Random, pose, points) -> list[tuple[float, float]]:
    """A triangle with a corner on one of the polygon's edges as the original places it (to rounding),
    or one with an edge through one of its vertices: the configurations whose verdict the last bits decide."""
    xs, ys = transform_exact(pose, points)
    k = rng.randrange(len(xs))
    x1, y1, x2, y2 = xs[k], ys[k], xs[(k + 1) % len(xs)], ys[(k + 1) % len(xs)]
    t = rng.choice([0.0, 1.0, rng.random(), rng.random() * 1e-12, 1 - rng.random() * 1e-12])
    cx, cy = x1 + t * (x2 - x1), y1 + t * (y2 - y1)
    nx, ny = (y2 - y1, x1 - x2) if rng.random() < 0.5 else (y1 - y2, x2 - x1)
    if rng.random() < 0.5:  # a corner on the edge
        return [(cx, cy), (cx + 3 * nx - (x2 - x1), cy + 3 * ny - (y2 - y1)),
                (cx + 3 * nx + (x2 - x1), cy + 3 * ny + (y2 - y1))]
    # an edge through the point, across the polygon's edge
    return [(cx - nx, cy - ny), (cx + nx, cy + ny), (cx + nx + (x2 - x1), cy + ny + (y2 - y1))]


def test_decided_answers_hold_for_every_placement_within_the_slack():
    """The fast loop on the plain placement either leaves a pair undecided or decides it as the all-pairs
    test does on the original's placement and on any other within the slack."""
    rng = random.Random(32)
    decided = undecided = 0
    for _ in range(300):
        pose = (rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-7, 7))
        shape = rng.choice([PLATE, *CONES])
        obstacles = ObstacleEdges([near_contact(rng, pose, shape)])
        xs, ys = transform_fast(pose, shape)
        slack = fast_error(REACH, max(abs(pose[0]), abs(pose[1])) + REACH)
        margins = tolerance(slack, 4 * REACH + obstacles.largest)
        placements = [transform_exact(pose, shape)]
        placements += [(nudged(rng, xs, slack), nudged(rng, ys, slack)) for _ in range(10)]
        if shape is PLATE:
            verdict = plate_collides(xs, ys, obstacles.polygons, margins)
            undecided += verdict is None
            decided += verdict is not None
            for px, py in placements if verdict is not None else ():
                assert plate_collides_exact(list(zip(px, py, strict=True)), obstacles.surfaces) == verdict
        else:
            found = cone_range(xs, ys, obstacles.polygons, 0.04, 0.3, margins)
            undecided += found is None
            decided += found is not None
            for px, py in placements if found is not None else ():
                d = cone_range_exact(list(zip(px, py, strict=True)), obstacles.surfaces, 0.04, 0.3)
                assert abs(d - found[0]) <= found[1]
    assert decided > 50 and undecided > 50  # both kinds are reached: the margins are neither 0 nor huge


def test_settled_raw_holds_for_every_distance_within_the_error():
    rng = random.Random(33)
    unsettled = 0
    for _ in range(3000):
        d = rng.uniform(0.04, 0.3)
        error = 10.0 ** rng.uniform(-16, -9)
        raw = settled_raw(d, error)
        if raw is None:
            unsettled += 1
            continue
        assert raw == distance_to_raw(d)
        for e in (-error, -error / 3, error / 2, error):
            assert distance_to_raw(d + e) == raw
    assert unsettled < 30  # only near a rounding boundary
    # a distance whose ADC input is a rounding boundary to 1e-12: unsettled even for 1e-15 m
    lo, hi = 0.1, 0.11
    for _ in range(80):
        mid = (lo + hi) / 2
        if ir_voltage(mid) * 1000 / 3 - 400.5 > 0:
            lo = mid
        else:
            hi = mid
    assert abs(ir_voltage(lo) * 1000 / 3 - 400.5) < 1e-9
    assert settled_raw(lo, 1e-15) is None and settled_raw(lo, 0.0) == distance_to_raw(lo)


def test_near_parallel_flags_every_culled_pair_the_formula_reports():
    """Cone side edges against obstacle edges on their own line, behind the apex or beyond the far point
    (boxes apart): whenever the formula reports such a pair, the heading is flagged for that cone. And the
    flagged headings are rare (a flag everywhere would pass the first half)."""
    world = load_world("week4")
    obstacles = ObstacleEdges(world.obstacles)
    rng = random.Random(34)
    reported = 0
    for _ in range(3000):
        pose = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-7, 7))
        i = rng.randrange(5)
        xs, ys = transform_exact(pose, CONES[i])
        k = rng.choice([0, 5])  # apex to the first far point, last far point to the apex
        a = (xs[k], ys[k], xs[(k + 1) % 6], ys[(k + 1) % 6])
        t3 = rng.choice([rng.uniform(1.05, 3.0), rng.uniform(-2.0, -0.05)])
        t4 = t3 + rng.uniform(0.05, 1.0) * (1 if t3 > 0 else -1)
        b = (a[0] + t3 * (a[2] - a[0]), a[1] + t3 * (a[3] - a[1]),
             a[0] + t4 * (a[2] - a[0]), a[1] + t4 * (a[3] - a[1]))
        if crossing(a, b) is None:
            continue
        reported += 1
        tri = [(b[0], b[1]), (b[2], b[3]), (b[0] + 0.3 * (a[1] - a[3]), b[1] + 0.3 * (a[2] - a[0]))]
        spans = [span(PLATE)] + [span(c) for c in CONES]
        index = NearParallel([PLATE, *CONES], spans, ObstacleEdges([tri]), REACH)
        assert i + 1 in index.flagged(*pose)
    assert reported > 30
    index = NearParallel([PLATE, *CONES], [span(PLATE)] + [span(c) for c in CONES], obstacles, REACH)
    flagged = sum(bool(index.flagged(0.0, 0.0, rng.uniform(-7, 7))) for _ in range(20000))
    assert flagged < 100  # under 0.5 % of headings in the week-4 world


# a triangle whose edges are parallel to no robot edge at heading 0 (no interval reaches 0 or pi: the
# look-up wraps round from the last interval to the first)
ODD_TRIANGLE = [(0.5, 0.5), (0.5 + math.cos(0.123), 0.5 + math.sin(0.123)), (0.2, 1.4)]


@pytest.mark.parametrize("obstacles", [load_world("week4").obstacles, [ODD_TRIANGLE]], ids=["week4", "odd"])
def test_near_parallel_remembers_free_headings_without_missing_an_interval(obstacles):
    """A robot turning slowly, both ways and past multiples of pi: the remembered free stretch never hides
    a flagged heading (each answer equals a fresh look-up's), and far out everything is flagged."""
    spans = [span(PLATE)] + [span(c) for c in CONES]
    index = NearParallel([PLATE, *CONES], spans, ObstacleEdges(obstacles), REACH)
    fresh = NearParallel([PLATE, *CONES], spans, ObstacleEdges(obstacles), REACH)
    rng = random.Random(35)
    headings, theta = [], -7.0
    while theta < 7.0:  # a slow turn, mostly one way
        theta += rng.uniform(-0.0002, 0.0012)
        headings.append(theta)
    # and, in order, the middle of every interval and the headings just either side of k*pi
    middles = [(lo + hi) / 2 for lo, hi in zip(index._starts[1:], index._ends[1:], strict=True)]
    sweep = sorted([k * math.pi + m for k in range(-2, 3) for m in middles]
                   + [k * math.pi + e for k in range(-2, 3) for e in (-1e-7, 1e-7)])
    flagged = 0
    for theta in headings + sweep + headings[::-1] + sweep[::-1]:  # turning left, then right
        fresh.free = (0.0, 0.0)
        got = index.flagged(0.2, -0.1, theta)
        assert got == fresh.flagged(0.2, -0.1, theta), theta
        flagged += bool(got)
    assert flagged > 10 * len(middles)  # every interval, in five turns of pi, both ways
    assert index.flagged(1e5, 0.0, 0.0) == frozenset(range(6)) == index.flagged(0.0, 0.0, 1e7)
    assert NearParallel([PLATE], spans[:1], ObstacleEdges([]), REACH).flagged(0.0, 0.0, 1.0) == frozenset()
