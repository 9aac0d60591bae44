"""What `grade` prints on a terminal: the per-check table of one result, wrapped to the terminal's width,
coloured only on a terminal.

Everything in it that a student can influence (names, paths, messages, replay lines) goes through
grader.untrusted.printable, as do the command's error lines and the batch's progress messages.
"""

from __future__ import annotations

import os
import sys
import textwrap
from typing import TextIO

from grader.sandbox.capabilities import LOCAL_ONLY
from grader.untrusted import printable

_COLOURS = {"ok": "32", "FAIL": "1;31", "ERROR": "33", "TIMEOUT": "35", "bold": "1", "dim": "2"}
_MARK = {"passed": "ok", "failed": "FAIL", "error": "ERROR", "timeout": "TIMEOUT"}
_WORDS = {"failed": "failed", "error": "error", "timeout": "timed out"}


def use_colour(stream: TextIO) -> bool:
    """Colour only on a terminal, and never when NO_COLOR is set (https://no-color.org) or TERM=dumb."""
    if os.environ.get("NO_COLOR") or os.environ.get("TERM") == "dumb":
        return False
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty())


def width(stream: TextIO) -> int:
    """Columns to wrap at: $COLUMNS if set, else the terminal's width, else 100 (a file or a pipe)."""
    columns = os.environ.get("COLUMNS", "")
    if columns.isdigit() and int(columns) > 0:
        return max(40, int(columns))
    try:
        if stream.isatty():
            return max(40, os.get_terminal_size(stream.fileno()).columns)
    except (AttributeError, OSError, ValueError):
        pass
    return 100


class Printer:
    """Writes lines to `stream`: untrusted parts made printable, wrapped to the width, coloured on a TTY."""

    def __init__(self, stream: TextIO) -> None:
        self.stream, self.colour, self.width = stream, use_colour(stream), width(stream)

    def paint(self, text: str, style: str) -> str:
        return f"\x1b[{_COLOURS[style]}m{text}\x1b[0m" if self.colour and style in _COLOURS else text

    def line(self, text: str = "") -> None:
        self.stream.write(text + "\n")

    def wrapped(self, text: object, indent: str) -> None:
        """Untrusted text, each of its lines wrapped to the width under `indent` (blank lines kept)."""
        for raw in printable(text).split("\n"):
            parts = textwrap.wrap(raw, max(20, self.width - len(indent)), break_on_hyphens=False,
                                  replace_whitespace=True, drop_whitespace=True) or [""]
            for part in parts:
                self.line((indent + part).rstrip())


def print_result(result: dict, out: TextIO | None = None) -> None:
    """The terminal table of one result: one line per passed check; a failed one with its message and
    the replay line; then the notes, what did not pass and the total, so that the end of the output (what
    a student sees first) says what to fix."""
    p = Printer(out if out is not None else sys.stdout)
    one = _one
    p.wrapped(f"week {one(result.get('week'))}: {one(result.get('submission', ''))}  (seed "
              f"{one(result.get('seed'))}, grader {one(result.get('grader_version', '?'))}, isolation "
              f"{one(result.get('isolation', '?'))})", "")
    if result.get("status") == "invalid":
        p.line(f"  {p.paint('INVALID', 'FAIL')}: the submission could not be graded:")
        p.wrapped(result.get("message", ""), "    ")
    checks = [c for c in result.get("checks") or [] if isinstance(c, dict)]
    id_width = max([len(one(c.get("id", ""))) for c in checks] + [10])
    indent = " " * 10
    said = None  # the last message printed: one broken file fails many checks with the same words
    for c in checks:
        status = str(c.get("status", ""))
        mark = _MARK.get(status, one(status))
        hidden = "  [hidden]" if c.get("visibility") == "hidden" else ""
        p.line(f"  {p.paint(f'{mark:7s}', mark)} {one(c.get('id', '')):{id_width}s} "
               f"{_points(c.get('points'))}/{_points(c.get('max_points'), 'g')}{hidden}".rstrip())
        if status == "passed":
            continue
        if c.get("message") and c["message"] == said:
            p.line(f"{indent}(the same reason as above)")
        elif c.get("message"):
            p.wrapped(c["message"], indent)
            said = c["message"]
        replay = (c.get("details") or {}).get("replay") if isinstance(c.get("details"), dict) else None
        if replay:
            # not wrapped: a command is copied and pasted whole (the terminal folds the long line)
            p.line(f"{indent}replay: {one(replay)}")
    note = str(result.get("isolation_note") or "")
    if note.startswith(LOCAL_ONLY):
        p.wrapped(note, "  ")
    numerics = result.get("numerics")
    if isinstance(numerics, dict) and numerics.get("note"):  # not official grading's numeric environment
        p.wrapped(f"numerics: {numerics['note']}", "  ")
    for note in result.get("notices") or []:
        p.wrapped(f"note: {note}", "  ")
    if not result.get("hidden") and not isinstance(result.get("practice"), dict):
        from simiam.course.weeks import hidden_variants

        n = result.get("hidden_checks_not_run", 0)
        ran = result.get("visible_checks", len(checks))
        vary = hidden_variants(result.get("week"))  # what the week's hidden checks vary
        verb = "runs" if n == 1 else "run"
        p.wrapped(f"{_count(ran, 'visible check')} ran here"
                  + (f"; {_count(n, 'hidden check')} ({vary}, drawn per seed) {verb} at official grading"
                     if n else "") + (_practice_hint(result.get("week")) if n else ""), "  ")
    lost = [c for c in checks if c.get("status") != "passed"]
    if lost:  # the end of the output is what a student sees first: what to fix, in the table's order
        p.line(f"  not passed ({len(lost)} of {len(checks)}):")
        for c in lost:
            points = f"{_points(c.get('points'), 'g')}/{_points(c.get('max_points'), 'g')}"
            p.line(f"    {one(c.get('id', '')):{id_width}s} {points:8s} "
                   f"{_WORDS.get(str(c.get('status')), 'not passed')}")
    elif checks:
        p.line(f"  all {_count(len(checks), 'check')} passed")
    practice = result.get("practice")
    if checks or not isinstance(practice, dict):  # --check of a hidden check with --practice grades nothing
        p.line(p.paint(f"  total: {_points(result.get('score'), 'g')} / "
                       f"{_points(result.get('max_score'), 'g')}", "bold"))
    if isinstance(practice, dict):
        _print_practice(p, practice, id_width)


def _practice_hint(week: object) -> str:
    """Where the week has a practice set: the command that tries variants like the hidden ones."""
    from grader.practice import WEEKS_WITH_PRACTICE, load_practice

    if type(week) is not int or week not in WEEKS_WITH_PRACTICE or load_practice(week) is None:
        return ""
    return f" (grade week{week} --practice tries practice variants drawn like them)"


def _print_practice(p: Printer, practice: dict, id_width: int) -> None:
    """`grade --practice`'s own section, after the total: the hidden checks run on the practice variants,
    with no points, and the note that says they are not the graded ones."""
    checks = [c for c in practice.get("checks") or [] if isinstance(c, dict)]
    variants = practice.get("variants")
    count = len(variants) if isinstance(variants, list) else 0
    title = f"  practice (not graded): the hidden checks on {_count(count, 'practice variant')}"
    p.line(p.paint(title, "bold"))
    indent = " " * 10
    for c in checks:
        status = str(c.get("status", ""))
        mark = _MARK.get(status, _one(status))
        p.line(f"  {p.paint(f'{mark:7s}', mark)} {_one(c.get('id', '')):{id_width}s} practice")
        if c.get("message"):  # passed too: it names the variants that ran
            p.wrapped(c["message"], indent)
    p.wrapped(practice.get("note", ""), "  ")
    lost = sum(1 for c in checks if c.get("status") != "passed")
    p.line(f"  practice: {len(checks) - lost} of {_count(len(checks), 'practice check')} passed "
           "(never part of the total)")


def _one(value: object) -> str:
    """Names, ids, paths and commands: one line each."""
    return printable(value, multiline=False)


def _points(value: object, fmt: str = "5.2f") -> str:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return "?"
    return format(value, fmt)


def _count(n: object, noun: str) -> str:
    return f"{n} {noun}{'' if n == 1 else 's'}"
