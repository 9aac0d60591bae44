"""The independent week-7 reference brain (instructor_tools/reference_week7.py) against the recordings, and
the solutions against it where nothing was recorded: every goal of the golden README at both time steps,
and every hidden variant (slow). Both must command the very same wheel speeds at every step."""

from __future__ import annotations

import math
from pathlib import Path

import mistakes
import pytest
from test_week7_fsm import CASES, ENDINGS, _cases
from week7_setup import WEEK7

from grader.checks.week7 import turned
from grader.hidden import load_hidden
from instructor_tools.reference_week7 import Week7Brain, solve_2x2
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.simulator import Simulator
from simiam.world import World, load_world

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize(("name", "case"), CASES)
def test_the_reference_brain_reproduces_the_recordings(name, case):
    rows = _cases(name)[case]
    dt = float(rows[1]["t"]) / int(rows[1]["step"])
    brain = Week7Brain(WEEK7.spec, (float(rows[0]["x_g"]), float(rows[0]["y_g"])))
    sim = Simulator(load_world(WEEK7.world), brain, WEEK7.spec, dt=dt)
    for row in rows[1:]:
        rec = sim.step()
        where = f"{name} case {case} step {rec.step}"
        assert math.dist(rec.pose[:2], (float(row["x"]), float(row["y"]))) < 1e-6, where
        assert (rec.vel_r, rec.vel_l) == (float(row["vel_r"]), float(row["vel_l"])), where
        assert (rec.command["state"], brain.switch_count) == (row["state"], int(row["switch_count"])), where
        assert (brain.fw_direction, brain.d_prog) == (row["fw_direction"], float(row["d_prog"])), where
        for side in ("left", "right"):
            recorded = float(row[f"sigma_{side}_1"]), float(row[f"sigma_{side}_2"])
            assert (side in brain.sigma) != math.isnan(recorded[0]), where
            if side in brain.sigma:
                assert brain.sigma[side] == recorded, where


def disagreement(folder: Path, world: World, goal: tuple[float, float], dt: float, seconds: float = 60.0):
    """The first step where the folder's code and the reference brain command different wheel speeds."""
    sub = load_submission(folder, WEEK7)
    assert sub.ok, sub.errors
    ours = Simulator(world, LocalBrain(sub, WEEK7, {"goal": goal}), WEEK7.spec, dt=dt)
    ref = Simulator(world, Week7Brain(WEEK7.spec, goal), WEEK7.spec, dt=dt)
    for _ in range(int(round(seconds / dt))):
        a, b = ours.step(), ref.step()
        if (a.vel_r, a.vel_l, a.command["state"]) != (b.vel_r, b.vel_l, b.command["state"]):
            return f"step {a.step}: {a.command['state']} ({a.vel_r!r}, {a.vel_l!r}) vs reference " \
                   f"{b.command['state']} ({b.vel_r!r}, {b.vel_l!r})"
        if a.collided or a.command["state"] == "stop":
            return None
    return None


@pytest.mark.parametrize("dt", sorted(ENDINGS))
def test_solutions_agree_with_the_reference_on_every_goal_of_the_readme(dt):
    for goal in ENDINGS[dt]:
        assert disagreement(ROOT / "solutions/week7", load_world(WEEK7.world), goal, dt) is None, goal


def test_the_cross_check_catches_a_wrong_automaton(tmp_path):
    folder = mistakes.build("submissions", "week7_wall_on_far_side", tmp_path, 7)
    assert disagreement(folder, load_world(WEEK7.world), (1.1, 1.1), 0.05)


@pytest.mark.slow
def test_solutions_agree_with_the_reference_on_every_hidden_variant():
    for v in load_hidden(7)["variants"]:
        world, goal = turned(load_world(WEEK7.world), tuple(v["goal"]), v["turn"], v["of"])
        assert disagreement(ROOT / "solutions/week7", world, goal, WEEK7.dt) is None, v


@pytest.mark.parametrize(("matrix", "b", "expected"), [
    ((0.0, 0.3, 0.0, -0.4), (0.8, 0.6), (0.0, (0.3 * 0.8 - 0.4 * 0.6) / 0.25)),   # u_gtg = 0
    ((0.5, 1.0, 0.25, 0.5), (0.75, 0.5), (0.32, 0.64)),   # parallel columns: u_ao = 2 u_gtg
])
def test_the_singular_systems_get_the_least_squares_solution_of_least_length(matrix, b, expected):
    import numpy as np

    a11, a12, a21, a22 = matrix
    got = solve_2x2(a11, a12, a21, a22, *b)
    lstsq = np.linalg.lstsq(np.array([[a11, a12], [a21, a22]]), np.array(b), rcond=None)[0]
    assert got == pytest.approx(tuple(lstsq), abs=1e-12)
    assert got == pytest.approx(expected, abs=1e-12)
