"""Imports the engine only for type hints: no circle, that import never runs."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from fakepkg.engine import run

NAME = "types"


def later(f: run) -> None:
    return None
