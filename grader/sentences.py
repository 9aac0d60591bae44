"""Messages built from parts: a check's words followed by a note, without the doubled punctuation that a
plain ". " join gives after a part that already ends a sentence ("did you mean 'avoid_obstacles'?. Note:")."""

from __future__ import annotations

_ENDS = (".", "?", "!")


def then(text: str, more: str) -> str:
    """`text`, then the sentence `more`: joined by ". " unless `text` already ends a sentence (then by a
    space), or `more` alone when `text` is empty. An empty `more` leaves `text` as it is."""
    if not more:
        return text
    if not text:
        return more
    return f"{text} {more}" if text.rstrip().endswith(_ENDS) else f"{text}. {more}"
