"""The week-6 world (worlds/week6.xml: the week-4 L and the arena walls) against world_w6.csv."""

from __future__ import annotations

from physics_golden import check_world

from simiam.world import load_world


def test_week6_world_vertices():
    res = check_world(load_world("week6").obstacles, "world_w6.csv")
    assert res["polygons"] == res["recorded"] == 6
    assert res["max_vertex_error"] <= 1e-12, res
    assert res["bit_exact"], res


def test_world_check_catches_the_week5_world():
    """A world with the right walls but other blocks (week 5's) is caught."""
    res = check_world(load_world("week5").obstacles, "world_w6.csv")
    assert res["max_vertex_error"] > 1e-3
