"""Text cut to a length, saying how much was cut: the one rule set for every capped text of the grader.

The rules (tests/sandbox/test_shorten.py):

- A limit counts characters (code points), never bytes, so a cut never splits a character; a caller
  bounding bytes picks a limit in characters that fits (grader.result_size).
- Text within the limit comes back unchanged. Longer text comes back in at most ``limit`` characters
  with the marker ``[... N characters cut here ...]`` where the text was cut; N is exactly the number of
  characters of the text that are not shown.
- :func:`keep_head` keeps the start (a message: what went wrong is said first). :func:`keep_ends` keeps
  the start and the end and cuts the middle (printed output: the first lines are where students look for
  their debug output, the last ones what ran just before the code stopped).
- The marker is set off by spaces, or with ``whole_lines`` on a line of its own; there the cut moves to
  line ends where that loses at most half of what each side keeps (a line cut inside reads as a wrong
  value), and a single long line is cut inside. The line break before the marker is the head's own line
  end where it has one (shown, so not counted in N); the one after the marker is the marker's.
- When even the marker does not fit, the text is cut to ``limit`` without one (a limit of 0 gives "").
- Only strings are cut. What to do with a value that is not one (a worker's reply with a number where
  a message belongs) is the caller's rule: grader.inside.caps.clip gives its default.

It lives in grader.inside because the worker's side may import nothing trusted
(tests/sandbox/test_inside.py); the grader's side imports it from here.
"""

from __future__ import annotations


def marker(cut: int) -> str:
    """The note that stands where ``cut`` characters were taken out."""
    return f"[... {cut} characters cut here ...]"


def keep_head(text: str, limit: int) -> str:
    """``text`` in at most ``limit`` characters: its start, then the marker."""
    if len(text) <= limit:
        return text
    room = limit - len(" " + marker(len(text)))  # the longest marker this text can need
    if room < 0:
        return text[:max(0, limit)]
    return f"{text[:room]} {marker(len(text) - room)}"


def keep_ends(text: str, limit: int, *, whole_lines: bool = False) -> str:
    """``text`` in at most ``limit`` characters: its start and its end with the marker between them."""
    if len(text) <= limit:
        return text
    room = limit - len(2 * " " + marker(len(text)))
    if room < 0:
        return text[:max(0, limit)]
    head, tail = text[:(room + 1) // 2], text[len(text) - room // 2:]
    if whole_lines:
        head, tail = _whole_lines(head, tail)
        if text[len(head):len(head) + 1] == "\n" and not head.endswith("\n"):
            head += "\n"  # a head cut just before a line end is whole: the marker's line break shows it
    shown_head = head[:-1] if whole_lines and head.endswith("\n") else head  # its newline sets off the marker
    gap = "\n" if whole_lines else " "
    return f"{shown_head}{gap}{marker(len(text) - len(head) - len(tail))}{gap}{tail}"


def _whole_lines(head: str, tail: str) -> tuple[str, str]:
    """``head`` back to its last line end and ``tail`` on from its first, each where that loses at most
    half of it."""
    if "\n" in head[len(head) // 2:]:
        head = head[: head.rindex("\n") + 1]
    if "\n" in tail[: len(tail) // 2]:
        tail = tail[tail.index("\n") + 1:]
    return head, tail
