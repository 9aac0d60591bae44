"""Imports the report at the top (one half of the circle)."""

from fakepkg import types_only
from fakepkg.leaf import LIMIT
from fakepkg.sub.report import render


def run() -> str:
    return render(LIMIT) + types_only.NAME
