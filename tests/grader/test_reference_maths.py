"""grader.reference holds no answers (issue 11), so its properties are held here to the instructor's
reference implementations (instructor_tools/reference_maths.py), and the expected values the checks read
as data (grader/checks/expected/) to what instructor tooling computes from them."""

from __future__ import annotations

import json
import math
import random

import pytest

from grader import reference as ref
from instructor_tools import expected
from instructor_tools.reference_maths import ensure_w_week3
from simiam.course.weeks import spec_for_week


def _cases(n: int = 2000) -> list[tuple[float, float]]:
    rng = random.Random(11)
    edges = [(0.0, 0.0), (0.25, 3.0), (-0.25, -3.0), (10.0, 1.0), (-10.0, -1.0), (0.0, 100.0), (1.0, -100.0)]
    return edges + [(rng.uniform(-0.6, 0.6), rng.uniform(-6.0, 6.0)) for _ in range(n)]


@pytest.mark.parametrize("week", [2, 3])
def test_ensure_w_command_is_what_the_reference_ensure_w_drives(week: int) -> None:
    """The property (keep w, give up the least v) gives the same (v, w) as the reference code, to 1e-12."""
    spec = spec_for_week(week)
    worst = 0.0
    for v, w in _cases():
        want = ref.diff_to_uni(spec, *ensure_w_week3(spec, v, w))
        got = ref.ensure_w_command(spec, v, w)
        worst = max(worst, abs(got[0] - want[0]), abs(got[1] - want[1]))
    assert worst < 1e-12


def test_a_wrong_property_would_be_seen() -> None:
    """The wrong version: giving up v as if the wheels were L apart (not L/2) differs from the reference."""
    spec = spec_for_week(3)
    v, w = 0.25, 3.0
    wrong_top = spec.wheel_radius * spec.max_vel - abs(w) * spec.wheel_base_length
    want = ref.diff_to_uni(spec, *ensure_w_week3(spec, v, w))[0]
    assert abs(min(v, wrong_top) - want) > 1e-3
    assert abs(ref.ensure_w_command(spec, v, w)[0] - want) < 1e-12


def test_the_placement_matrix_is_the_course_s_transformation() -> None:
    """matrix_of reads the matrix off the simulator's placement; it is the course's [cos -sin x] matrix."""
    rng = random.Random(4)
    for _ in range(500):
        x, y, theta = rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-7, 7)
        c, s = math.cos(theta), math.sin(theta)
        course = [[c, -s, x], [s, c, y], [0.0, 0.0, 1.0]]
        got = ref.matrix_of(x, y, theta)
        assert all(got[i][j] == course[i][j] for i in range(3) for j in range(3))
        px, py = rng.uniform(-1, 1), rng.uniform(-1, 1)
        placed = ref.place((x, y, theta), (px, py))
        assert math.dist(placed, (c * px - s * py + x, s * px + c * py + y)) < 1e-12


def test_points_at_and_bearing() -> None:
    assert ref.points_at(math.pi / 4, 1.0, 1.0) < 1e-15
    assert abs(ref.points_at(0.0, -1.0, 0.0) - math.pi) < 1e-15
    assert abs(ref.points_at(-3.1, -1.0, 0.0) - 0.0415926535897931) < 1e-12  # across +-pi, not 6.2 rad
    assert ref.bearing(0.0, -1.0) == -math.pi / 2


def test_the_expected_values_are_what_instructor_tooling_computes() -> None:
    """python -m instructor_tools.expected --check: the shipped data matches the reference maths."""
    assert expected.main(["--check"]) == 0


def test_drifted_expected_values_are_caught(tmp_path, monkeypatch, capsys) -> None:
    """The wrong version: a shipped table whose estimate was edited by hand."""
    for name in expected.TABLES:
        table = json.loads((expected.FOLDER / name).read_text())
        table["estimate"][0] += 1e-9
        (tmp_path / name).write_text(expected.render(table))
    monkeypatch.setattr(expected, "FOLDER", tmp_path)
    assert expected.main(["--check"]) == 1
    assert "out of date" in capsys.readouterr().err
