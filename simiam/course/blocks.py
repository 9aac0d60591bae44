"""START/END code blocks: find them, name them, and splice a submission's blocks into pristine stubs.

A code block is the region between a line `# START CODE BLOCK` and a line `# END CODE BLOCK` (any
indentation, any case, trailing text allowed: `# START CODE BLOCK  [week 3: theta_g]`). A block is
identified by its file, the function or class around it (`QBSupervisor.update_odometry`, `<module>` at top
level) and its position among the blocks of that scope, so that moving a whole function around does not
confuse the matching.

Splicing a submission into the stubs (the grader's trust boundary) lives in `simiam.course.splice`, stub
generation in `simiam.course.stubs` (docs/design.md lists all three under blocks.py).
"""

from __future__ import annotations

import ast
import hashlib
import re
from dataclasses import dataclass
from functools import lru_cache

_MARKER = re.compile(r"^(?P<indent>[ \t]*)#+\s*(?P<kind>START|END)\s+CODE\s+BLOCK\b(?P<rest>.*)$", re.I)
_WEEK_TAG = re.compile(r"week\s*(\d+)", re.I)
MODULE_SCOPE = "<module>"
MAX_BLOCKS = 200  # a stub has a handful; thousands would only slow the grader down
MAX_PARSED_LINES = 5000


class BlockError(Exception):
    """A problem with the code blocks of one file, located at a line (1-based) of that file."""

    def __init__(self, file: str, line: int | None, message: str) -> None:
        super().__init__(message)
        self.file = file
        self.line = line
        self.message = message

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}" if self.line else self.file
        return f"{where}: {self.message}"

    def to_json(self) -> dict:
        return {"file": self.file, "line": self.line, "message": self.message}


@dataclass(frozen=True)
class Block:
    """One START/END region. Lines are 1-based; `body` is the text between the two marker lines."""

    file: str
    ordinal: int  # 1-based position among the blocks of the file
    scope: str  # enclosing class/function path, e.g. "GoToGoal.execute"
    occurrence: int  # 1-based position among the blocks of the same scope
    start_line: int
    end_line: int
    indent: str  # indentation of the START line
    tag: str  # text after START CODE BLOCK, stripped ("" if none)
    body: str

    @property
    def key(self) -> tuple[str, int]:
        """What identifies the block inside its file: (scope, occurrence)."""
        return (self.scope, self.occurrence)

    @property
    def week(self) -> int | None:
        """The week named in the START tag, if the tag says one (`[week 3: theta_g]` -> 3)."""
        m = _WEEK_TAG.search(self.tag)
        return int(m.group(1)) if m else None

    def describe(self) -> str:
        return f"{self.scope} (block {self.occurrence})" if self.occurrence > 1 else self.scope


_LINE = re.compile(r"[^\r\n]*(?:\r\n|\n|\r)|[^\r\n]+$")


def source_lines(text: str, keepends: bool = True) -> list[str]:
    """Lines as Python counts them: split at \\n, \\r\\n and \\r only (str.splitlines also splits at form
    feeds and Unicode separators, which would put error lines off and could fake a marker line)."""
    lines = _LINE.findall(text)
    return lines if keepends else [ln.rstrip("\r\n") for ln in lines]


def marker(line: str) -> re.Match | None:
    """The START/END marker match of one line, or None."""
    return _MARKER.match(line.rstrip("\r\n"))


_KEPT_TEXT = 64 * 1024  # characters: the course's files are a few KB; a larger text is not kept


def find_blocks(text: str, file: str) -> list[Block]:
    """All code blocks of `text`, in order. Raises BlockError for unbalanced or nested markers."""
    if len(text) <= _KEPT_TEXT:
        return list(_kept_blocks(text, file))
    return list(_blocks_of(text, file))


def _blocks_of(text: str, file: str) -> tuple[Block, ...]:
    lines = source_lines(text)
    spans: list[tuple[int, int, str, str]] = []  # (start index, end index, indent, tag)
    open_at: int | None = None
    open_indent = open_tag = ""
    for i, line in enumerate(lines):
        m = marker(line)
        if not m:
            continue
        if m.group("kind").upper() == "START":
            if open_at is not None:
                raise BlockError(
                    file,
                    i + 1,
                    f"START CODE BLOCK inside the block opened at line {open_at + 1}"
                    " (is that block's END CODE BLOCK missing?)",
                )
            if len(spans) == MAX_BLOCKS:
                raise BlockError(file, i + 1, f"more than {MAX_BLOCKS} code blocks in one file")
            open_at, open_indent = i, m.group("indent").expandtabs(8)
            open_tag = m.group("rest").strip(" \t%#-")
        else:
            if open_at is None:
                raise BlockError(file, i + 1, "END CODE BLOCK without a START CODE BLOCK before it")
            spans.append((open_at, i, open_indent, open_tag))
            open_at = None
    if open_at is not None:
        raise BlockError(file, open_at + 1, "START CODE BLOCK has no END CODE BLOCK after it")
    scopes = _scopes(lines, spans)
    blocks: list[Block] = []
    seen: dict[str, int] = {}
    for n, ((s, e, indent, tag), scope) in enumerate(zip(spans, scopes, strict=True), start=1):
        seen[scope] = seen.get(scope, 0) + 1
        blocks.append(
            Block(file, n, scope, seen[scope], s + 1, e + 1, indent, tag, "".join(lines[s + 1 : e]))
        )
    return tuple(blocks)


# find_blocks's work kept per text: a grading process finds the blocks of the same skeletons and shipped
# files for every student of a batch. Blocks are frozen, an error is raised again each time (not kept), and
# at most 256 texts of at most _KEPT_TEXT characters are kept (16 MB at worst, hostile files included).
_kept_blocks = lru_cache(maxsize=256)(_blocks_of)


def _scopes(lines: list[str], spans: list[tuple[int, int, str, str]]) -> list[str]:
    """The enclosing def/class path of each block.

    Each block is replaced by a `pass` on its START line so that the rest of the file parses even when a body
    does not. The `pass` goes at the marker's indentation, or else at the body's (a marker moved to column 0
    inside a method); if neither parses (edits outside the blocks), the scope is read from indentation."""
    marker_indents = [len(indent) for _, _, indent, _ in spans]
    body_indents = [_body_indent(lines[s + 1 : e]) or len(indent) for s, e, indent, _ in spans]
    # Parsing a huge file costs seconds of the grader's time; its scopes are read from indentation instead.
    for indents in (marker_indents, body_indents) if len(lines) <= MAX_PARSED_LINES else ():
        skeleton = list(lines)
        for (s, e, _, _), width in zip(spans, indents, strict=True):
            skeleton[s] = " " * width + "pass\n"
            skeleton[s + 1 : e + 1] = ["\n"] * (e - s)
        try:
            tree = ast.parse("".join(skeleton))
        except (SyntaxError, ValueError, RecursionError, MemoryError):
            continue
        return [_enclosing(tree, s + 1) for s, _, _, _ in spans]
    return [
        _scope_by_indent(lines, s, max(m, b))
        for (s, _, _, _), m, b in zip(spans, marker_indents, body_indents, strict=True)
    ]


def _enclosing(tree: ast.Module, line: int) -> str:
    """Dotted names of the defs and classes around `line`, descending only through the statements that
    contain it (walking the whole tree would be slow on a huge file)."""
    names: list[str] = []
    kids: list = tree.body
    while kids:
        node = next((k for k in kids if k.lineno <= line <= (k.end_lineno or k.lineno)), None)
        if node is None:
            break
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.append(node.name)
        kids = [k for k in _child_statements(node) if hasattr(k, "lineno")]
    return ".".join(names) or MODULE_SCOPE


def _child_statements(node: ast.AST) -> list:
    out: list[ast.AST] = []
    for name in ("body", "orelse", "finalbody", "handlers", "cases"):
        for child in getattr(node, name, None) or []:
            # match_case has no line numbers of its own: look straight into its body
            out.extend(child.body if isinstance(child, ast.match_case) else [child])
    return out


def _body_indent(body: list[str]) -> int:
    """Smallest indentation (tabs as 8 columns) of the body's code lines; 0 if it has none."""
    code = [ln.expandtabs(8) for ln in body if ln.strip() and not ln.lstrip().startswith("#")]
    return min((len(ln) - len(ln.lstrip()) for ln in code), default=0)


DEF_LINE = re.compile(r"^([ \t]*)(?:async\s+)?(?:def|class)\s+([A-Za-z_]\w*)")


def _scope_by_indent(lines: list[str], start: int, indent: int) -> str:
    names: list[str] = []
    limit = indent
    for line in reversed(lines[:start]):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        width = len(line.expandtabs(8)) - len(line.expandtabs(8).lstrip())
        if width >= limit:
            continue
        m = DEF_LINE.match(line.expandtabs(8))
        if m:
            names.append(m.group(2))
        limit = width
        if limit == 0:
            break
    return ".".join(reversed(names)) or MODULE_SCOPE


def def_line(text: str, scope: str) -> int:
    """The line of the `def`/`class` that ends `scope` (0 if not found)."""
    name = scope.rsplit(".", 1)[-1]
    for i, line in enumerate(source_lines(text, keepends=False), start=1):
        m = DEF_LINE.match(line)
        if m and m.group(2) == name:
            return i
    return 0


def dedent_body(body: str) -> str:
    """The body with its common indentation removed (tabs count as 8 columns, comment lines do not count)."""
    lines = source_lines(body, keepends=False)
    lines = [_expand_leading_tabs(ln) for ln in lines]
    code = [ln for ln in lines if ln.strip() and not ln.lstrip().startswith("#")]
    common = min((len(ln) - len(ln.lstrip()) for ln in code), default=0)
    out = []
    for ln in lines:
        lead = len(ln) - len(ln.lstrip())
        out.append("" if not ln.strip() else ln[min(common, lead) :] if lead >= common else ln.lstrip())
    return "\n".join(out) + ("\n" if out else "")


def _expand_leading_tabs(line: str) -> str:
    rest = line.lstrip(" \t")
    return line[: len(line) - len(rest)].expandtabs(8) + rest


def indent_body(dedented: str, indent: str) -> str:
    """Put a dedented body at `indent` (blank lines stay empty)."""
    return "".join(indent + ln if ln.strip() else "\n" for ln in source_lines(dedented))


def fingerprint(body: str) -> str | None:
    """A hash of what the body *does* (its AST), so that comments and layout do not count; None if it
    does not parse."""
    try:
        tree = ast.parse(dedent_body(body))
    except (SyntaxError, ValueError):
        return None
    return hashlib.sha256(ast.dump(tree).encode()).hexdigest()[:16]


def replace_bodies(text: str, blocks: list[Block], bodies: dict[int, str]) -> str:
    """`text` with the body of block `ordinal` replaced by `bodies[ordinal]` (already indented)."""
    lines = source_lines(text)
    for b in sorted((b for b in blocks if b.ordinal in bodies), key=lambda b: -b.start_line):
        new = bodies[b.ordinal]
        if new and not new.endswith("\n"):
            new += "\n"
        lines[b.start_line : b.end_line - 1] = source_lines(new)
    return "".join(lines)

