"""WRONG IR models, each a `ranger(pose) -> (ranges, raws, apexes)` in the final world."""
import math

from simiam.physics.ir_ranging import cone_range, cone_range_exact
from simiam.physics.segments import ObstacleEdges
from simiam.physics.transform import transform_fast
from simiam.robot.ir_sensor import distance_to_raw, ir_voltage, mounted_cone
from simiam.course.weeks import spec_for_week
from simiam.world import load_world

SPEC = spec_for_week(4)
OBSTACLES = ObstacleEdges(load_world("final").obstacles)


def _range(xs, ys, lo, hi):
    """The fast ranging where it decides, else the all-pairs one (the right parts these models reuse)."""
    found = cone_range(xs, ys, OBSTACLES.polygons, lo, hi)
    return found[0] if found else cone_range_exact(list(zip(xs, ys)), OBSTACLES.surfaces, lo, hi)


def centre_ray(pose):
    """A single ray along the sensor axis instead of the 6-vertex cone."""
    ranges, raws, apexes = [], [], []
    for mount in SPEC.ir_mounts:
        ray = [mount[:2], (mount[0] + 0.3 * math.cos(mount[2]), mount[1] + 0.3 * math.sin(mount[2]))]
        xs, ys = transform_fast(pose, ray)
        # a degenerate 2-vertex "polygon": the ray and its way back
        d = _range(xs, ys, 0.04, 0.3)
        ranges.append(d)
        raws.append(distance_to_raw(d, "week3"))
        apexes.append((xs[0], ys[0]))
    return ranges, raws, apexes


def bankers_round(pose):
    """The right cone, but Python's round (half to even) and no clamp at the minimum range."""
    ranges, raws, apexes = [], [], []
    for mount in SPEC.ir_mounts:
        xs, ys = transform_fast(pose, mounted_cone(mount, 0.3, SPEC.ir_spread))
        d = _range(xs, ys, 0.0, 0.3)
        ranges.append(d)
        raws.append(min(max(round(ir_voltage(d) * 1000 / 3), 133), 917))
        apexes.append((xs[0], ys[0]))
    return ranges, raws, apexes


def mirrored_mounts(pose):
    """Mirror-symmetric sensor mounts (the original's are not)."""
    ranges, raws, apexes = [], [], []
    mounts = [(-0.0474, 0.0534, math.pi / 2), (0.0613, 0.0244, math.pi / 4), (0.0636, 0.0, 0.0),
              (0.0613, -0.0244, -math.pi / 4), (-0.0474, -0.0534, -math.pi / 2)]
    for mount in mounts:
        xs, ys = transform_fast(pose, mounted_cone(mount, 0.3, SPEC.ir_spread))
        d = _range(xs, ys, 0.04, 0.3)
        ranges.append(d)
        raws.append(distance_to_raw(d, "week3"))
        apexes.append((xs[0], ys[0]))
    return ranges, raws, apexes


def cone_polygon_arc_angles(r, spread):
    """WRONG cone: far points at exactly +-spread/2 and +-spread/4 on the circle (the original puts them at
    +-asin(tan(spread/2)) and +-asin(tan(spread/4)): its y offsets are r*tan, not r*sin)."""
    pts = [(0.0, 0.0)]
    for a in (spread / 2, spread / 4, 0.0, -spread / 4, -spread / 2):
        pts.append((r * math.cos(a), r * math.sin(a)))
    return tuple(pts)
