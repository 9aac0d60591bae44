"""Splice a submission's code blocks into the pristine stubs: the grader's trust boundary.

Only the bodies of the START/END blocks are taken from a submission; everything outside them comes from the
stub, and edits made there are reported, never run. A block that is missing, duplicated or does not parse
keeps the stub's placeholder, with an error naming the submission's file and line.
"""

from __future__ import annotations

import ast
import difflib
import os
import re
import stat
from dataclasses import dataclass, field
from pathlib import Path

from simiam.course.blocks import (
    Block,
    BlockError,
    dedent_body,
    def_line,
    find_blocks,
    indent_body,
    marker,
    replace_bodies,
    source_lines,
)

MAX_FILE_BYTES = 256 * 1024  # a student file is a few kB; anything larger is refused, not read
MAX_DIFF_LINES = 3000  # the outside diff is quadratic at worst: beyond this, one summary entry


# ----------------------------------------------------------------------------------------------- splicing


@dataclass
class OutsideEdit:
    """Lines of the submission that differ from the stub outside the blocks (reported, never run)."""

    file: str
    first_line: int  # in the submission, 1-based
    last_line: int
    diff: str

    def __str__(self) -> str:
        span = (
            f"{self.first_line}"
            if self.first_line >= self.last_line
            else f"{self.first_line}-{self.last_line}"
        )
        # One line (reports list these next to other messages); the full hunk stays in `diff`.
        lines = [ln.strip() for ln in self.diff.splitlines() if ln[1:].strip()]
        shown = "; ".join(ln[0] + " " + ln[1:].strip() for ln in lines)
        if len(shown) > 160:
            shown = shown[:157] + "..."
        return f"{self.file}:{span}: changed outside the code blocks (not used): {shown}"

    def to_json(self) -> dict:
        return {
            "file": self.file,
            "first_line": self.first_line,
            "last_line": self.last_line,
            "diff": self.diff,
        }


@dataclass
class SpliceResult:
    """The stub with the submission's blocks in it, and what happened on the way."""

    file: str
    text: str
    blocks_taken: list[str] = field(default_factory=list)  # "GoToGoal.execute", ... (from the submission)
    blocks_kept: list[str] = field(default_factory=list)  # stub placeholders kept because of an error
    outside_edits: list[OutsideEdit] = field(default_factory=list)
    errors: list[BlockError] = field(default_factory=list)
    missing: bool = False  # the submission has no such file: the stub is used as it is

    @property
    def ok(self) -> bool:
        return not self.errors and not self.missing

    def to_json(self) -> dict:
        return {
            "file": self.file,
            "blocks_taken": self.blocks_taken,
            "blocks_kept": self.blocks_kept,
            "outside_edits": [e.to_json() for e in self.outside_edits],
            "errors": [e.to_json() for e in self.errors],
            "missing": self.missing,
        }


def match_blocks(
    stub: list[Block], sub: list[Block], file: str, sub_text: str = ""
) -> tuple[dict[int, Block], list[BlockError]]:
    """Pair each stub block (by ordinal) with the submission's block of the same scope and occurrence.

    A scope whose number of blocks differs from the stub's is not matched at all (markers deleted or
    duplicated: which body belongs where is a guess, and the grader does not guess)."""
    by_scope: dict[str, list[Block]] = {}
    for b in sub:
        by_scope.setdefault(b.scope, []).append(b)
    stub_scopes: dict[str, list[Block]] = {}
    for b in stub:
        stub_scopes.setdefault(b.scope, []).append(b)
    pairs: dict[int, Block] = {}
    errors: list[BlockError] = []
    for scope, want in stub_scopes.items():
        got = by_scope.get(scope, [])
        if len(got) == len(want):
            pairs.update({w.ordinal: _pair_by_tag(w, want, got) for w in want})
        elif len(got) > len(want):
            extra = _first_extra(want, got)
            errors.append(
                BlockError(
                    file,
                    extra.start_line,
                    f"{scope} has {len(got)} code blocks, the stub has "
                    f"{len(want)} (duplicated START/END lines?)",
                )
            )
        else:
            line = got[-1].start_line if got else def_line(sub_text, scope) or None
            errors.append(
                BlockError(
                    file,
                    line,
                    f"{scope} has {len(got)} code block(s), the stub has {len(want)} "
                    "(START/END lines deleted?)",
                )
            )
    for scope, got in by_scope.items():
        if scope not in stub_scopes:
            errors.append(
                BlockError(
                    file, got[0].start_line, f"code block in {scope}, where the stub has none (ignored)"
                )
            )
    return pairs, errors


def _first_extra(want: list[Block], got: list[Block]) -> Block:
    """The block that looks added: the first repeat of a tag the stub has once, else the first surplus."""
    seen: set[str] = set()
    for g in got:
        if g.tag and g.tag in seen and sum(w.tag == g.tag for w in want) == 1:
            return g
        seen.add(g.tag)
    return got[len(want)]


def _pair_by_tag(want: Block, wants: list[Block], got: list[Block]) -> Block:
    tags = [w.tag for w in wants]
    if want.tag and len(set(tags)) == len(tags) and sorted(tags) == sorted(g.tag for g in got):
        return next(g for g in got if g.tag == want.tag)  # reordered inside one function: the tags say which
    return got[want.occurrence - 1]


def check_body(
    stub_text: str, stub_blocks: list[Block], target: Block, sub_block: Block, file: str
) -> tuple[str | None, BlockError | None]:
    """The submission's body re-indented for the stub, or the error that keeps it out.

    The body must parse on its own (so it cannot open a bracket or a string that swallows the stub's code
    after it) and the stub must compile with it in place."""
    odd = odd_indent(sub_block.body)
    if odd is not None:
        offset, char = odd
        return None, BlockError(
            file,
            sub_block.start_line + offset,
            f"this line of the code block of {sub_block.describe()} is indented with {char}; "
            "indent with spaces only (Python would move the line out of its function)",
        )
    dedented = dedent_body(sub_block.body)
    try:
        ast.parse(dedented)
    except (RecursionError, MemoryError, ValueError) as e:  # absurdly nested code, or NUL bytes
        return None, BlockError(
            file,
            sub_block.start_line,
            f"the code block of {sub_block.describe()} cannot be read: {type(e).__name__}",
        )
    except SyntaxError as e:
        return None, BlockError(
            file,
            sub_block.start_line + (e.lineno or 1),
            f"syntax error in the code block of {sub_block.describe()}: {_plain(e.msg)}",
        )
    body = indent_body(dedented, target.indent)
    text = replace_bodies(stub_text, stub_blocks, {target.ordinal: body})
    try:
        compile(text, file, "exec", dont_inherit=True)
    except (SyntaxError, ValueError, RecursionError, MemoryError) as e:
        line = getattr(e, "lineno", None) or 0
        offset = line - target.start_line
        in_block = 0 < offset <= body.count("\n")
        where = sub_block.start_line + offset if in_block else sub_block.start_line
        return None, BlockError(
            file,
            where,
            f"the code block of {sub_block.describe()} does not fit where it stands: {getattr(e, 'msg', e)}",
        )
    return body, None


_WHITESPACE_NAMES = {"\f": "a form feed (\\f)", "\v": "a vertical tab (\\v)"}


def odd_indent(body: str) -> tuple[int, str] | None:
    """(1-based line within the body, what it is) of the first code line indented with anything but spaces
    and tabs. Python resets the indentation at a form feed, so such a line could leave the block's function
    and run at module level; other odd whitespace (vertical tab, no-break space) is refused alike."""
    for n, line in enumerate(source_lines(body, keepends=False), start=1):
        code = line.lstrip()
        if not code:
            continue
        for ch in line[: len(line) - len(code)]:
            if ch not in " \t":
                return n, _WHITESPACE_NAMES.get(ch, f"the character U+{ord(ch):04X}")
    return None


def _plain(msg: str) -> str:
    """Python's message without its "(detected at line N)", which counts lines of the body, not the file."""
    return re.sub(r"\s*\(detected at line \d+\)", "", msg)


def splice(stub_text: str, submission_text: str, filename: str) -> SpliceResult:
    """The stub with every block body taken from the submission.

    Blocks are matched by enclosing function and position; a block that is missing, duplicated or does
    not parse keeps the stub's placeholder and yields an error naming the submission's file and line.
    Edits outside the blocks are listed in `outside_edits` and not used."""
    stub_blocks = find_blocks(stub_text, filename)  # the stub is ours: a broken one is a bug, let it raise
    result = SpliceResult(filename, stub_text)
    try:
        sub_blocks = find_blocks(submission_text, filename)
    except BlockError as e:
        result.errors.append(BlockError(e.file, e.line, e.message + " (no block of this file can be taken)"))
        result.blocks_kept = [b.describe() for b in stub_blocks]
        return result  # no outside diff: without its blocks the whole file would be listed
    pairs, result.errors = match_blocks(stub_blocks, sub_blocks, filename, submission_text)
    bodies: dict[int, str] = {}
    for b in stub_blocks:
        sub = pairs.get(b.ordinal)
        body, err = check_body(stub_text, stub_blocks, b, sub, filename) if sub else (None, None)
        if body is None:
            result.blocks_kept.append(b.describe())
            if err:
                result.errors.append(err)
        else:
            bodies[b.ordinal] = body
            result.blocks_taken.append(b.describe())
    result.text = replace_bodies(stub_text, stub_blocks, bodies)
    try:
        compile(result.text, filename, "exec", dont_inherit=True)
    except (SyntaxError, ValueError, RecursionError, MemoryError) as e:  # cannot happen today: use the stub
        result.errors.append(BlockError(filename, None, f"the code blocks do not compile together: {e}"))
        result.blocks_kept, result.blocks_taken, result.text = (
            [b.describe() for b in stub_blocks],
            [],
            stub_text,
        )
    result.outside_edits = outside_edits(stub_text, stub_blocks, submission_text, sub_blocks, filename)
    return result


def outside_edits(
    stub_text: str, stub_blocks: list[Block], sub_text: str, sub_blocks: list[Block], file: str
) -> list[OutsideEdit]:
    """Hunks where the submission differs from the stub outside the blocks (trailing spaces ignored)."""
    a = _outside_lines(stub_text, stub_blocks)
    b = _outside_lines(sub_text, sub_blocks)
    if max(len(a), len(b)) > MAX_DIFF_LINES:
        last = b[-1][0] if b else 1
        return [OutsideEdit(file, 1, last, f"+({len(b)} lines outside the blocks, the stub has {len(a)})")]
    edits = []
    # Compare without indentation: re-indenting a whole file changes nothing worth reporting.
    matcher = difflib.SequenceMatcher(
        None, [t.strip() for _, t in a], [t.strip() for _, t in b], autojunk=False
    )
    for tag, i1, i2, j1, j2 in matcher.get_opcodes():
        if tag == "equal":
            continue
        removed = [f"-{t}" for _, t in a[i1:i2]]
        added = [f"+{t}" for _, t in b[j1:j2]]
        if j2 > j1:
            first, last = b[j1][0], b[j2 - 1][0]
        else:
            first = last = b[j1][0] if j1 < len(b) else (b[-1][0] + 1 if b else 1)
        edits.append(OutsideEdit(file, first, last, "\n".join(removed + added)))
    return edits


def _outside_lines(text: str, blocks: list[Block]) -> list[tuple[int, str]]:
    inside: set[int] = set()
    for b in blocks:
        inside.update(range(b.start_line + 1, b.end_line))
    out = []
    for n, line in enumerate(source_lines(text, keepends=False), start=1):
        if n in inside:
            continue
        m = marker(line)
        out.append((n, f"{m.group('indent')}# {m.group('kind').upper()} CODE BLOCK" if m else line.rstrip()))
    return out


# ------------------------------------------------------------------------------------------------ folders


@dataclass
class FolderSpliceReport:
    """What `splice_folder` did, file by file."""

    files: dict[str, SpliceResult] = field(default_factory=dict)
    extra_files: list[str] = field(default_factory=list)  # in the submission, not in the stub: ignored

    @property
    def missing_files(self) -> list[str]:
        return [name for name, r in self.files.items() if r.missing]

    @property
    def errors(self) -> list[BlockError]:
        return [e for r in self.files.values() for e in r.errors]

    @property
    def ok(self) -> bool:
        return all(r.ok for r in self.files.values())

    def messages(self) -> list[str]:
        """One line per problem, for a student to read."""
        out = [
            f"{name}: file missing from the submission; the stub's version is used"
            for name in self.missing_files
        ]
        out += [str(e) for e in self.errors]
        out += [f"{name}: not part of the assignment (ignored)" for name in self.extra_files]
        return out

    def to_json(self) -> dict:
        return {
            "files": {n: r.to_json() for n, r in self.files.items()},
            "extra_files": self.extra_files,
            "missing_files": self.missing_files,
            "ok": self.ok,
        }


def read_submission_file(path: Path, file: str) -> str:
    """The text of one untrusted submission file: a regular file (never a link), small, UTF-8."""
    try:
        st = os.lstat(path)
    except OSError as e:
        raise BlockError(file, None, f"cannot read the file: {e.strerror}") from None
    if stat.S_ISLNK(st.st_mode) or not stat.S_ISREG(st.st_mode):
        raise BlockError(file, None, "not a regular file (links are not followed)")
    if st.st_size > MAX_FILE_BYTES:
        raise BlockError(file, None, f"file is {st.st_size} bytes, more than the {MAX_FILE_BYTES} allowed")
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    with os.fdopen(fd, "rb") as f:
        data = f.read(MAX_FILE_BYTES + 1)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        line = data[: e.start].count(b"\n") + 1
        raise BlockError(file, line, "not valid UTF-8 text") from None


def splice_folder(stub_dir: Path, submission_dir: Path, out_dir: Path) -> FolderSpliceReport:
    """Splice every `.py` file of `stub_dir` with the same file of `submission_dir` into `out_dir`.

    Files missing from the submission (or unreadable) are copied from the stub and reported; other files of
    the stub folder (README.md, ...) are not copied; files only in the submission are listed and ignored."""
    stub_dir, submission_dir, out_dir = Path(stub_dir), Path(submission_dir), Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    report = FolderSpliceReport()
    for stub_path in sorted(stub_dir.glob("*.py")):
        name = stub_path.name
        stub_text = stub_path.read_text(encoding="utf-8")
        sub_path = submission_dir / name
        if not os.path.lexists(sub_path):
            result = SpliceResult(
                name,
                stub_text,
                blocks_kept=[b.describe() for b in find_blocks(stub_text, name)],
                missing=True,
            )
        else:
            try:
                result = splice(stub_text, read_submission_file(sub_path, name), name)
            except BlockError as e:
                result = SpliceResult(
                    name,
                    stub_text,
                    errors=[e],
                    blocks_kept=[b.describe() for b in find_blocks(stub_text, name)],
                )
        (out_dir / name).write_text(result.text, encoding="utf-8")
        report.files[name] = result
    stub_names = set(report.files)
    if submission_dir.is_dir():
        report.extra_files = sorted(
            p.name for p in submission_dir.iterdir() if p.suffix == ".py" and p.name not in stub_names
        )
    return report
