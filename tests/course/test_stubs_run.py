"""Every stub folder loads and runs: the robot stays still (weeks 1-2) or drives straight (weeks 3-5)."""

import importlib.util
import shutil
from pathlib import Path

import pytest

from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).parents[2]
DATA = Path(__file__).parents[1] / "data" / "blocks"
SECONDS = 3.0
EXPECTED = {1: "still", 2: "still", 3: "straight", 4: "straight", 5: "straight"}  # week 5: heading 0


def behaviour(folder: Path, week: int) -> str:
    """'still', 'straight', 'turns', 'moves' (not straight from the start) or 'crash: ...'."""
    cfg = get_week(week)
    sub = load_submission(folder, cfg)
    if sub.errors:
        return f"crash: {sub.errors[0]}"
    try:
        sim = Simulator(
            load_world(cfg.world), LocalBrain(sub, cfg), spec=cfg.spec, dt=cfg.dt, start=cfg.start
        )
        ending = sim.run(seconds=SECONDS).ending
        if ending.broken:
            raise ending.error
    except Exception as e:  # noqa: BLE001 - a stub that crashes is exactly what this reports
        return f"crash: {type(e).__name__}: {e}"
    finally:
        sub.unload()
    x, y, theta = sim.pose
    x0, y0, theta0 = cfg.start
    if sim.collided:
        return "collided"
    if (x, y, theta) == (x0, y0, theta0):
        return "still"
    if abs(theta - theta0) > 1e-9:
        return "turns"
    return "straight" if abs(y - y0) < 1e-9 and x - x0 > 0.05 else "moves"


@pytest.mark.parametrize("week", sorted(EXPECTED))
def test_stub_runs(week):
    assert behaviour(ROOT / "assignments" / f"week{week}", week) == EXPECTED[week]


def _wrong_stubs():
    spec = importlib.util.spec_from_file_location("wrong_stubs", DATA / "wrong_stubs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.WRONG_STUBS


@pytest.mark.parametrize("index", range(4))
def test_wrong_stub_is_caught(index, tmp_path):
    week, file, old, new, what = _wrong_stubs()[index]
    folder = tmp_path / f"week{week}"
    shutil.copytree(ROOT / "assignments" / f"week{week}", folder)
    text = (folder / file).read_text()
    assert old in text
    (folder / file).write_text(text.replace(old, new, 1))
    got = behaviour(folder, week)
    assert got != EXPECTED[week]
    assert got.startswith(what), got
