"""One student's result stays under a fixed size, whatever their code sends back.

Every field that comes from the worker is capped where it enters the grader (grader.inside.caps),
but a message can still be repeated per check, per file and per run. This is the last bound: a result
whose JSON is larger than :data:`MAX_RESULT_BYTES` has its longest texts and lists cut, more and more,
until it fits; the cut is recorded under ``"truncated"``. Scores, statuses and check ids are never cut.
The HTML report gets the same bound (:func:`bound_html`): an oversized page is replaced, never served.
"""

from __future__ import annotations

import json
from typing import Any

from grader.inside.shorten import keep_ends

MAX_RESULT_BYTES = 2_000_000
MAX_HTML_BYTES = 2_000_000
# (longest text, longest list or dict) allowed at each round; the last one always fits
_ROUNDS = ((20_000, 2_000), (4_000, 500), (1_000, 100), (200, 20))
_KEEP = frozenset({"id", "status", "points", "max_points", "score", "max_score", "week", "seed"})


def result_bytes(result: dict) -> int:
    """The size of ``result`` as the batch writes it (indented JSON)."""
    return len(json.dumps(result, indent=2, sort_keys=True, default=str).encode("utf-8", "replace"))


def bound_result(result: dict, limit: int = MAX_RESULT_BYTES) -> dict:
    """``result`` itself when it fits in ``limit`` bytes, else a copy with texts and lists cut to fit."""
    size = result_bytes(result)
    if size <= limit:
        return result
    for text, items in _ROUNDS:
        cut = _clip(result, text, items, 0)
        cut["truncated"] = (f"this result was {size} bytes, over the {limit} byte limit; texts were cut to "
                            f"{text} characters and lists to {items} items")
        if result_bytes(cut) <= limit:
            return cut
    checks = [{k: c.get(k) for k in _KEEP | {"name", "kind", "message"} if k in c}
              for c in result.get("checks") or [] if isinstance(c, dict)][:500]
    bare = {k: result[k] for k in _KEEP | {"status", "submission", "grader_version", "batch"} if k in result}
    return _clip({**bare, "checks": checks, "truncated": f"this result was {size} bytes; only the scores "
                  "are kept"}, 200, 20, 0)


def _clip(value: Any, text: int, items: int, depth: int) -> Any:
    if isinstance(value, str):
        return keep_ends(value, text)
    if depth > 24:
        return None
    if isinstance(value, list):
        return [_clip(v, text, items, depth + 1) for v in value[:items]]
    if isinstance(value, dict):
        kept = list(value.items())
        kept = [kv for kv in kept if kv[0] in _KEEP] + [kv for kv in kept if kv[0] not in _KEEP][:items]
        return {_clip(k, 200, items, depth + 1) if isinstance(k, str) else k: _clip(v, text, items, depth + 1)
                for k, v in kept}
    return value


def bound_html(html: str, limit: int = MAX_HTML_BYTES) -> str | None:
    """``html`` when it fits in ``limit`` bytes, else None (the caller writes a short page instead)."""
    return html if len(html) <= limit // 4 or len(html.encode("utf-8", "replace")) <= limit else None
