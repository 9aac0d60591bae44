"""A wrong similarity page kept for tests/similarity/test_similarity_browser.py: code that neither wraps
nor scrolls inside its own box, in columns that grow with it (the page runs off a 1024 px window)."""

from __future__ import annotations

FIXED = ("minmax(0,1fr) minmax(0,1fr)", "white-space:pre-wrap;overflow-wrap:anywhere;max-height:30em;overflow:auto;")
WRONG = ("auto auto", "white-space:pre;")


def wrong_template(template: str) -> str:
    """``template`` with the page's wrapping taken out (each part must be there to be taken out)."""
    for fixed, wrong in zip(FIXED, WRONG, strict=True):
        assert fixed in template, f"the page's CSS no longer has {fixed!r}: update this wrong version"
        template = template.replace(fixed, wrong)
    return template
