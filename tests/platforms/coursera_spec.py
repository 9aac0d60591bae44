"""Coursera's custom-grader output (v2), as a validator the Coursera tests hold each feedback to.

coursera/programming-assignments-demo, custom-graders/v2/README.md: the grader writes /shared/feedback.json,
{"fractionalScore": 0.2, "feedback": "..."}, optionally "feedbackType": "HTML" (or "TXT") with the rich
feedback in /shared/htmlFeedback.html (txtFeedback.txt), which learners are then shown instead. The checks
on fractionalScore (a number, not a boolean, 0 <= x <= 1) and on `feedback` being present are those of
coursera/coursera_autograder's `grade local`.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

KEYS = {"fractionalScore", "feedback", "feedbackType"}
RICH = {"HTML": "htmlFeedback.html", "TXT": "txtFeedback.txt"}


def coursera_violations(shared: Path) -> list[str]:
    """What in shared/feedback.json (and the rich feedback it names) breaks Coursera's contract."""
    try:
        data = json.loads((shared / "feedback.json").read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        return [f"feedback.json cannot be read as JSON: {exc}"]
    if not isinstance(data, dict):
        return ["feedback.json is not a JSON object"]
    bad = [f"unknown key {k!r}" for k in data if k not in KEYS]
    score = data.get("fractionalScore")
    if type(score) not in (int, float) or not math.isfinite(score) or not 0 <= score <= 1:
        bad.append(f"fractionalScore {score!r} must be a number in [0, 1]")
    if not isinstance(data.get("feedback"), str):
        bad.append("feedback must be a string")
    kind = data.get("feedbackType")
    if kind is not None:
        if kind not in RICH:
            bad.append(f"feedbackType {kind!r} is not HTML or TXT")
        elif not (shared / RICH[kind]).is_file() or not (shared / RICH[kind]).read_text(encoding="utf-8"):
            bad.append(f"feedbackType {kind} but {RICH[kind]} is missing or empty")
    return bad
