"""Similarity tests: this folder on sys.path (similarity_class), and the class folder built once."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from similarity_class import build_class  # noqa: E402


@pytest.fixture(scope="module")
def week3_class(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The week-3 class of similarity_class (solutions, independent versions, planted copies, stubs)."""
    return build_class(tmp_path_factory.mktemp("similarity") / "class")
