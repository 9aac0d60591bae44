"""Shared helpers for the simulator tests: loading the wrong implementations kept as test data."""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType

DATA = Path(__file__).resolve().parents[1] / "data"


def wrong(name: str) -> ModuleType:
    path = DATA / "wrong_physics" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"wrong_physics_{name}", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
