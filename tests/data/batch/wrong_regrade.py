"""Wrong versions of the regrade bookkeeping that tests/batch/test_batch_regrade.py must catch (data)."""

from __future__ import annotations

from pathlib import Path


def archive_nothing(out: Path, stem: str, stored: dict) -> str:
    """Forgets the earlier result (what a plain overwrite did)."""
    return f"history/{stem}/not-kept.json"


def no_reasons(old: dict, new: dict, asked: str | None = None) -> list[str]:
    """Says nothing of why a student was graded again."""
    return []


def digest_of_seed_only(week: int, seed: int) -> dict:
    """A hidden set identity that is only the seed: an edited hidden set looks the same."""
    return {"seed": seed, "checks": [], "file": "", "file_sha256": "", "variants": [], "digest": str(seed)}
