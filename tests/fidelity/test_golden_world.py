"""The final world's obstacle vertices (world_walls.csv, and world_w7.csv: the week-7 world is the final one)
from worlds/final.xml, with the literal 1.5708."""

from __future__ import annotations

from physics_golden import DATA, check_world

from simiam.world import load_world


def test_final_world_vertices():
    res = check_world(load_world("final").obstacles)
    assert res["polygons"] == res["recorded"]
    assert res["max_vertex_error"] <= 1e-12, res
    assert res["bit_exact"], res


def test_week7_world_is_the_final_world():
    """The week-7 world (the trap around the start) is the original's final world, vertex for vertex."""
    res = check_world(load_world("final").obstacles, "world_w7.csv")
    assert res["polygons"] == res["recorded"] == 10
    assert res["bit_exact"], res


def test_world_check_catches_exact_pi_over_2():
    res = check_world(load_world(DATA / "wrong_physics" / "final_exact_pi_over_2.xml").obstacles)
    assert res["max_vertex_error"] > 1e-12
