"""Untrusted text made visible: what a student controls (file and folder names, printed output, exception
messages, state names) shown with every invisible character that acts on its surroundings as an escape.

On a terminal such characters act on the screen: an escape sequence recolours or clears it, moves the
cursor or retitles the window, a carriage return or backspace hides what came before, so that a FAIL
reads as "ok". In a page and on a terminal alike a bidi override reverses the text after it (a name that
reads as another student's) and zero-width characters make two names look the same. `printable` shows
each of them as `\\x1b`, `\\r`, `\\u202e`...; ordinary text, accents, Greek and emoji stay as they are.
The terminal output (grader.terminal, grader.batch.progress) and the pages (grader.report, the batch
summary and fallback page) pass student text through it; HTML escaping is the templates' job.
"""

from __future__ import annotations

import re
import unicodedata

# Anything outside printable ASCII is looked at one character at a time (most text never gets there).
_SUSPECT = re.compile(r"[^\n\t -~]")
_SUSPECT_ONE_LINE = re.compile(r"[^ -~]")
# Unicode categories that print nothing visible of their own but act on the terminal or on the text
# around them: controls (C0, DEL, C1 including CSI and OSC), format characters (bidi overrides and
# isolates, zero-width characters), lone surrogates, line and paragraph separators.
_HIDDEN = {"Cc", "Cf", "Cs", "Zl", "Zp"}
_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def _escape(ch: str) -> str:
    if ch in _NAMED:
        return _NAMED[ch]
    cp = ord(ch)
    return f"\\x{cp:02x}" if cp < 0x100 else f"\\u{cp:04x}" if cp < 0x10000 else f"\\U{cp:08x}"


def printable(text: object, *, multiline: bool = True) -> str:
    """`text` (any object, as `str()`) safe to show: control characters (escape sequences, carriage
    return, backspace, bell), format characters (bidi overrides, zero-width) and lone surrogates become
    visible escapes such as `\\x1b`. Newlines and tabs stay when `multiline` (Windows line ends become
    plain ones); otherwise newlines show as `\\n` and tabs become spaces, for text that must stay on one
    line (names, ids, paths, commands)."""
    text = str(text)
    if multiline:
        text = text.replace("\r\n", "\n")

    def one(match: re.Match) -> str:
        ch = match.group()
        if ch == "\n" or ch == "\t":
            return ch if multiline else (" " if ch == "\t" else _NAMED[ch])
        return _escape(ch) if unicodedata.category(ch) in _HIDDEN else ch

    return (_SUSPECT if multiline else _SUSPECT_ONE_LINE).sub(one, text)
