"""Wrong on purpose: grader.clearance.pose_bounds with the plate's box placed at the robot's position but
never turned with it (as if theta were always 0). Where the robot drives sideways to a wall its plate
reaches further than this box, the bound exceeds the true gap, and min_clearance skips the very step that
holds the smallest one. tests/grader/test_same_after_issue24.py shows its comparison catches this."""

import math

from grader.clearance import directions


def pose_bounds(plate, poses, shapes):
    bx, by = [p[0] for p in plate], [p[1] for p in plate]
    cx, cy = (min(bx) + max(bx)) / 2, (min(by) + max(by)) / 2
    hx, hy = (max(bx) - min(bx)) / 2, (max(by) - min(by)) / 2
    out = []
    for x, y, _ in poses:
        best = math.inf
        for shape in shapes:
            apart = -math.inf
            for dx, dy in directions(shapes):
                along = [dx * px + dy * py for px, py in shape.points]
                p = dx * (x + cx) + dy * (y + cy)
                h = hx * abs(dx) + hy * abs(dy)
                apart = max(apart, p - h - max(along), min(along) - p - h)
            best = min(best, apart)
        out.append(best)
    return out
