"""The sliding tests of week 7 against the original's recording (slidingmode_sigma.csv, the course author's
sigma = [u_gtg u_ao] \\ u_fw in sliding_left/sliding_right of 230acb3).

For each recorded input (estimate, goal, raw IR) the solutions' supervisor runs check_event("sliding_left")
and ("sliding_right"); u_gtg, u_ao, u_fw (SlidingMode's POINT, as the original stores it), theta_fw, sigma
and the event's value must match the recording (the vectors to 1e-12, sigma relative to 1e-9; this
machine's numpy reproduces them bit for bit, which the test reports but does not demand). The recorded
singular case (goal = estimate: u_gtg = 0, rcond 0) is held back in the team copy, so singular systems are
built here: sigma is the least-squares sigma of least length, and the robot is not sliding at the goal.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import mistakes
import numpy as np
import pytest
from week7_setup import WEEK7

from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests/data/golden/slidingmode_sigma.csv"


def _rows() -> list[dict]:
    with GOLDEN.open() as f:
        return list(csv.DictReader(f))


def supervisor(folder: Path):
    sub = load_submission(folder, WEEK7)
    assert sub.ok, sub.errors
    return LocalBrain(sub, WEEK7).supervisor


def put(sup, row: dict) -> None:
    """The recorded input: raw IR readings, the estimate and the goal."""
    sup.robot.update({"ticks": [0, 0], "ir_raw": [int(row[f"ir_raw_{i}"]) for i in range(1, 6)]})
    sup.state_estimate.set_pose((float(row["x"]), float(row["y"]), float(row["theta"])))
    sup.goal = (float(row["x_g"]), float(row["y_g"]))


def differences(folder: Path) -> tuple[list[str], int]:
    """What differs from the recording (to the tolerances above), and how many rows were not bit-exact."""
    sup = supervisor(folder)
    problems, inexact = [], 0
    for row in _rows():
        put(sup, row)
        where = f"case {row['case']} {row['direction']}"
        sliding = sup.check_event(f"sliding_{row['direction']}")
        mode = sup.sliding_mode
        got = {
            "u_gtg": [float(v) for v in mode.u_gtg], "u_ao": [float(v) for v in mode.u_ao],
            "u_fw": [float(v) for v in mode.u_fw], "theta_fw": [float(mode.theta_g)],
            "sigma": [float(v) for v in getattr(sup, f"sigma_{row['direction']}")],
        }
        for key, tol in (("u_gtg", 1e-12), ("u_ao", 1e-12), ("u_fw", 1e-12), ("theta_fw", 1e-12),
                         ("sigma", 1e-9)):
            columns = [key] if key == "theta_fw" else (
                ["sigma_1", "sigma_2"] if key == "sigma" else [f"{key}_x", f"{key}_y"])
            want = [float(row[c]) for c in columns]
            if any(abs(g - w) > tol * max(1.0, abs(w)) for g, w in zip(got[key], want, strict=True)):
                problems.append(f"{where}: {key} {got[key]}, recorded {want}")
            inexact += got[key] != want
        if bool(sliding) != (row["sliding"] == "1"):
            problems.append(f"{where}: sliding {sliding}, recorded {row['sliding']}")
    return problems, inexact


def test_solutions_reproduce_the_recorded_sliding_tests():
    problems, inexact = differences(ROOT / "solutions/week7")
    assert not problems, problems[:5]
    print(f"{len(_rows())} recorded sliding tests; values not bit-exact: {inexact}")


def test_the_recording_has_sliding_and_not_sliding_rows():
    rows = _rows()
    assert {r["direction"] for r in rows} == {"left", "right"}
    assert 0 < sum(r["sliding"] == "1" for r in rows) < len(rows)


def test_sigma_with_the_matrix_transposed_is_caught(tmp_path):
    folder = mistakes.build("submissions", "week7_sigma_rows", tmp_path, 7)
    problems, _ = differences(folder)
    assert any("sigma" in p for p in problems)


@pytest.mark.parametrize("direction", ["left", "right"])
def test_at_the_goal_the_system_is_singular_and_the_robot_is_not_sliding(direction):
    """u_gtg = 0 (the goal is the estimate; the recording's case 4, rcond 0): no exception, sigma is the
    least-squares sigma of least length, (0, (u_ao . u_fw) / |u_ao|^2), and the event is False."""
    sup = supervisor(ROOT / "solutions/week7")
    row = _rows()[0]
    put(sup, row)
    sup.goal = (float(row["x"]), float(row["y"]))
    assert sup.check_event(f"sliding_{direction}") is False
    mode = sup.sliding_mode
    assert list(mode.u_gtg) == [0.0, 0.0]
    sigma = getattr(sup, f"sigma_{direction}")
    expected = float(np.dot(mode.u_ao, mode.u_fw) / np.dot(mode.u_ao, mode.u_ao))
    assert sigma[0] == 0.0 and sigma[1] == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(("scale", "fw", "sliding"), [(2.0, (3.0, 1.0), True), (-1.0, (0.5, 2.0), False)])
def test_parallel_u_gtg_and_u_ao_give_a_least_squares_sigma(scale, fw, sliding):
    """u_ao a multiple of u_gtg: np.linalg.solve refuses the matrix; the least-squares sigma is used (for
    u_ao = 2 u_gtg it lies along (1, 2), so both entries are positive and the robot is sliding)."""
    sup = supervisor(ROOT / "solutions/week7")
    u_gtg = np.array([1.0, 0.0])
    sup.sliding_vectors = lambda direction: (u_gtg, scale * u_gtg, np.array(fw))
    assert sup.check_event("sliding_left") is sliding
    sigma = np.asarray(sup.sigma_left, dtype=float)
    assert np.all(np.isfinite(sigma))
    lstsq = np.linalg.lstsq(np.column_stack((u_gtg, scale * u_gtg)), np.array(fw), rcond=None)[0]
    assert sigma == pytest.approx(lstsq, rel=1e-12)
    assert math.isclose(float(sigma[1]), scale * float(sigma[0]), rel_tol=1e-12)
