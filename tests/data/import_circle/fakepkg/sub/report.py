"""Imports the engine back inside a function (the other half of the circle), relative to its package."""

from ..leaf import LIMIT


def render(n: int) -> str:
    from .. import engine

    return f"{n}/{LIMIT} {engine.__name__}"
