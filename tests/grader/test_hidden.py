"""The instructor's hidden week-4 variants are fair: the reference solution survives every one of them."""

from __future__ import annotations

from pathlib import Path

import pytest

from grader.checks.week4 import HIDDEN_SECONDS, _variant
from grader.hidden import load_hidden
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week
from simiam.simulator import Simulator
from simiam.world import load_world

ROOT = Path(__file__).resolve().parents[2]


def test_hidden_set_is_present_and_big_enough() -> None:
    data = load_hidden(4)
    assert data is not None and len(data["variants"]) >= 10


@pytest.mark.slow
def test_reference_solution_survives_every_hidden_variant() -> None:
    config = get_week(4)
    solution = load_submission(ROOT / "solutions" / "week4", 4)
    crashed = []
    for v in load_hidden(4)["variants"]:
        world = _variant(load_world("week4"), v["turn"], v["of"], v["mirror"])
        brain = LocalBrain(solution, config, config.settings.as_dict())
        trace = Simulator(world, brain, config.spec, dt=config.dt).run(HIDDEN_SECONDS)
        if trace.collision is not None:
            crashed.append((world.name, trace.collision["t"]))
    assert crashed == []
