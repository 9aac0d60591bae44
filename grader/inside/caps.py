"""Text that comes back from the student's worker, made safe to store, print and repeat.

Everything the worker sends is attacker-controlled: an error's file, line, message and type, the load
report's module and attribute names, state names, probe values. Two rules hold at the grader's side of
the pipe: no lone surrogate survives (JSON allows ``"\\ud800"``, UTF-8 writers do not), and no text is
kept longer than the cap of the field it fills.
"""

from __future__ import annotations

from typing import Any

from grader.inside.shorten import keep_head

FILE_CHARS = 200          # a file name inside the submission
TYPE_CHARS = 100          # an exception type
NAME_CHARS = 100          # a module, attribute or state name
MESSAGE_CHARS = 1000      # an error message
MAX_MODULES = 16        # a week has at most six student files
MAX_NAMES = 100           # attribute names listed per module (only membership is used)
MAX_ERRORS = 20           # load errors kept


def without_surrogates(text: str) -> str:
    """``text`` with every lone surrogate replaced by U+FFFD."""
    if not any("\ud800" <= ch <= "\udfff" for ch in text):
        return text
    return "".join("\ufffd" if "\ud800" <= ch <= "\udfff" else ch for ch in text)


def clip(value: Any, limit: int, default: str = "") -> str:
    """``value`` as a string of at most ``limit`` characters, its start kept (grader.inside.shorten), or
    ``default`` if it is not a string: a number where the worker owes a message is not one."""
    if not isinstance(value, str):
        return default
    return keep_head(without_surrogates(value), limit)


def clean(value: Any, depth: int = 0) -> Any:
    """A decoded JSON value with lone surrogates replaced in every string and key (depth-bounded)."""
    if isinstance(value, str):
        return without_surrogates(value)
    if depth > 64:
        return value
    if isinstance(value, list):
        return [clean(v, depth + 1) for v in value]
    if isinstance(value, dict):
        return {without_surrogates(k): clean(v, depth + 1) for k, v in value.items()}
    return value
