"""The four text cutters the grader had before grader.inside.shorten, as they were (one rule set each)."""

from typing import Any


def caps_clip(value: Any, limit: int, default: str = "") -> str:
    """grader.inside.caps.clip: a fixed 25 characters of room, so a limit under 25 is not kept."""
    if not isinstance(value, str):
        return default
    return value if len(value) <= limit else value[: limit - 25] + f" [... {len(value) - limit + 25} more]"


def official_cap(text: object, limit: int) -> str:
    """grader.platforms.official.cap: 40 characters of room, so a limit of 0 keeps all but 40."""
    text = "" if text is None else str(text)
    if len(text) <= limit:
        return text
    return text[: limit - 40] + f"\n... [{len(text) - limit + 40} characters cut]"


def cut_middle(text: str, limit: int) -> str:
    """grader.sandbox.output.cut_middle: under 60 characters the note alone is over the limit, and
    blank lines before the cut are dropped without being counted."""
    if len(text) <= limit:
        return text
    half = max(0, limit - 60) // 2
    head, tail = text[:half], text[len(text) - half:]
    if "\n" in head[len(head) // 2:]:
        head = head[: head.rindex("\n") + 1]
    if "\n" in tail[: len(tail) // 2]:
        tail = tail[tail.index("\n") + 1:]
    cut = len(text) - len(head) - len(tail)
    return f"{head.rstrip(chr(10))}\n[... {cut} characters cut here ...]\n{tail}"


def result_size_clip(value: str, text: int) -> str:
    """grader.result_size._clip on a string: keeps `text` characters plus the note (over the limit), and
    a limit of 0 keeps everything (value[-0:] is the whole string)."""
    return value if len(value) <= text else \
        value[:text // 2] + f" [... {len(value) - text} characters cut ...] " + value[-text // 2:]
