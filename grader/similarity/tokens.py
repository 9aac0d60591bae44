"""A code block as the comparer sees it: Python tokens with the names, comments and layout taken out.

Every name that is not a keyword becomes ``V`` (a renamed variable, attribute or function compares equal),
strings become ``S``, numbers keep their value (``2`` and ``2.0`` are one token), comments and blank lines
are dropped, a statement's end is one token (``;``) and indentation counts only as the block's nesting.
Each token keeps where it came from in the text, so that a match can be marked on the student's own code.

Read with the standard ``tokenize`` module; student text need not be valid Python, so where tokenize
gives up (an unterminated string, an inconsistent dedent) the rest is read with a plain regular
expression that never fails. Nothing is ever executed or parsed into a tree.
"""

from __future__ import annotations

import io
import keyword
import re
import tokenize
from dataclasses import dataclass

_DROPPED = {tokenize.COMMENT, tokenize.NL, tokenize.ENCODING, tokenize.ENDMARKER}
# where tokenize gives up: a name, a number, a string (a quote to the end of its line), an operator
_FALLBACK = re.compile(
    r"(?P<comment>#[^\r\n]*)|(?P<name>[^\W\d]\w*)|(?P<number>\d[\w.]*|\.\d[\w.]*)"
    r"|(?P<string>'[^'\r\n]*'?|\"[^\"\r\n]*\"?)|(?P<newline>\r\n|\n|\r)|(?P<space>[ \t\f\\]+)|(?P<op>.)",
    re.S,
)


@dataclass(frozen=True)
class Token:
    """One normalised token and the span of text (character offsets) it was read from."""

    text: str
    start: int
    end: int


def normalised(kind: int, text: str) -> str:
    """The comparer's word for one token: keywords and operators as written, every other name ``V``,
    strings ``S``, numbers by value."""
    if kind == tokenize.NAME:
        return text if keyword.iskeyword(text) else "V"
    if kind == tokenize.STRING:
        return "S"
    if kind == tokenize.NUMBER:
        return _number(text)
    if kind == tokenize.NEWLINE:
        return ";"
    if kind == tokenize.INDENT:
        return "{"
    if kind == tokenize.DEDENT:
        return "}"
    return text


def _number(text: str) -> str:
    try:
        value = float(text.replace("_", ""))
    except ValueError:
        return text.lower()  # 0x1f, 1j: as written
    if not abs(value) <= 1e15:   # huge, or beyond a float (inf): as written (its first 32 characters)
        return text.lower()[:32]
    return str(int(value)) if value == int(value) else repr(value)


def block_tokens(text: str) -> list[Token]:
    """The normalised tokens of ``text`` (a dedented block body) with their character offsets."""
    starts = _line_starts(text)
    tokens: list[Token] = []
    reached = 0
    try:
        for tok in tokenize.generate_tokens(io.StringIO(text).readline):
            start = starts[tok.start[0] - 1] + tok.start[1] if tok.start[0] <= len(starts) else len(text)
            end = starts[tok.end[0] - 1] + tok.end[1] if tok.end[0] <= len(starts) else len(text)
            if tok.type == tokenize.ERRORTOKEN and not tok.string.strip():
                continue
            if tok.type not in _DROPPED and not (tok.type == tokenize.NEWLINE and not tok.string):
                tokens.append(Token(normalised(tok.type, tok.string), start, max(end, start)))
            reached = max(reached, end)
    except (tokenize.TokenError, SyntaxError, ValueError):
        tokens.extend(_fallback(text, reached))
    return tokens


def _fallback(text: str, start: int) -> list[Token]:
    out: list[Token] = []
    for m in _FALLBACK.finditer(text, start):
        kind, word = m.lastgroup, m.group()
        if kind in ("comment", "space") or (kind == "newline" and out and out[-1].text == ";"):
            continue
        if kind == "name":
            word = word if keyword.iskeyword(word) else "V"
        elif kind == "number":
            word = _number(word)
        elif kind == "string":
            word = "S"
        elif kind == "newline":
            word = ";"
        out.append(Token(word, m.start(), m.end()))
    return out


def _line_starts(text: str) -> list[int]:
    """Offset of the first character of each line, as tokenize counts lines (\\n, \\r\\n, \\r)."""
    starts = [0]
    for m in re.finditer(r"\r\n|\n|\r", text):
        starts.append(m.end())
    return starts
