"""Batch tests: this folder on sys.path (the grading processes import batch_fake_grader from it)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from batch_helpers import load_wrong  # noqa: E402


@pytest.fixture
def wrong() -> object:
    """tests/data/batch/wrong_batch.py: the wrong implementations the tests must catch."""
    return load_wrong()
