"""WRONG collision test: open intervals (0 < u < 1), so touching is not a collision."""
from simiam.physics.segments import polygon_edges


def plate_collides(plate, obstacle_polygons):
    for x1, y1, x2, y2 in polygon_edges(plate):
        for poly in obstacle_polygons:
            for x3, y3, x4, y4 in polygon_edges(poly):
                d = (y4 - y3) * (x2 - x1) - (x4 - x3) * (y2 - y1)
                if d == 0:
                    continue
                ua = ((x4 - x3) * (y1 - y3) - (y4 - y3) * (x1 - x3)) / d
                ub = ((x2 - x1) * (y1 - y3) - (y2 - y1) * (x1 - x3)) / d
                if 0 < ua < 1 and 0 < ub < 1:
                    return True
    return False


def plate_collides_with_containment(plate, obstacle_polygons):
    """Also reports a plate wholly inside an obstacle (the original does not)."""
    if plate_collides(plate, obstacle_polygons):
        return True
    x, y = plate[0]
    for poly in obstacle_polygons:
        xs = [p[0] for p in poly]
        ys = [p[1] for p in poly]
        if min(xs) <= x <= max(xs) and min(ys) <= y <= max(ys):
            return True
    return False
