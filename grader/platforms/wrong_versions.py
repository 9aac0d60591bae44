"""Wrong versions kept as mistakes: a unified diff against solutions/weekN, applied to a fresh copy.

A `<name>.patch` starts with one `# <name>: what the mistake is` line, optionally a
`# aims: week3.go_to_goal.error_wrap [more ids]` line (the checks it must lose; `none` for a correct
alternative that must keep full marks: `grade selfcheck` and the test suite hold every wrong version to
it), optionally more `# ` lines saying why (say, why it also loses a scenario check), then a unified
diff whose paths name the solution file it changes (`--- a/solutions/week3/go_to_goal.py`). The applier is
strict: every hunk's old lines must stand in the file exactly (at the stated line, or else at exactly one
other place), or `MistakeError` says which file and hunk no longer fit, so that a change to solutions/
cannot silently leave a wrong version behind.
"""

from __future__ import annotations

import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

_HUNK = re.compile(r"@@ -(\d+)(?:,(\d+))? \+(\d+)(?:,(\d+))? @@")
# a file of the week's folder by its plain name: no folder part, no `.` or `..`, no leading dot
_PATH = re.compile(r"[ab]/solutions/week(\d)/(\w[\w.]*)$")
AIMS = "# aims:"


class MistakeError(Exception):
    """A mistake that cannot be read or no longer applies to the current solutions."""


@dataclass
class Hunk:
    header: str
    old_start: int
    old: list[str] = field(default_factory=list)
    new: list[str] = field(default_factory=list)


@dataclass
class Mistake:
    """One wrong version: what it is, the solution week it changes, and the hunks per file."""

    why: str
    week: int
    files: dict[str, list[Hunk]]
    aims: frozenset[str] | None = None   # the check ids it must lose (empty: it must lose none); None: unsaid


def read_mistake(path: Path) -> Mistake:
    """Parse a `.patch` file (the title line, an optional `# aims:` line, then a unified diff against
    solutions/weekN). Anything that is not such a file (a folder named x.patch, text that is not UTF-8, a
    file that cannot be read) is a MistakeError saying so, as a patch that does not parse is."""
    if not path.is_file():
        raise MistakeError(f"{path}: not a file (a wrong version is one .patch file)")
    try:
        lines = path.read_bytes().decode("utf-8").splitlines(keepends=True)
    except UnicodeDecodeError as exc:
        raise MistakeError(f"{path}: not UTF-8 text (byte {exc.start + 1})") from None
    except OSError as exc:
        raise MistakeError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    if not lines or not lines[0].startswith("# "):
        raise MistakeError(f"{path}: the first line must be '# <what the mistake is>'")
    why = lines[0][2:].strip()
    aims: frozenset[str] | None = None
    k = 1
    if len(lines) > 1 and lines[1].startswith(AIMS):
        said = lines[1][len(AIMS):].replace(",", " ").split()
        aims = frozenset() if said == ["none"] else frozenset(said)
        k = 2
    week: int | None = None
    files: dict[str, list[Hunk]] = {}
    hunks: list[Hunk] = []
    while k < len(lines):
        line = lines[k]
        if line.startswith("--- "):
            old_path = _PATH.match(line[4:].strip())
            new_line = lines[k + 1] if k + 1 < len(lines) else ""
            new_path = _PATH.match(new_line[4:].strip()) if new_line.startswith("+++ ") else None
            if not old_path or not new_path or old_path.groups() != new_path.groups():
                raise MistakeError(f"{path}:{k + 1}: want '--- a/solutions/weekN/F' then '+++ b/(same)'")
            if week is not None and int(old_path[1]) != week:
                raise MistakeError(f"{path}:{k + 1}: all files of one mistake must come from one week")
            week, name = int(old_path[1]), old_path[2]
            if name in files:
                raise MistakeError(f"{path}:{k + 1}: {name} appears twice")
            hunks = files[name] = []
            k += 2
        elif line.startswith("@@"):
            head = _HUNK.match(line)
            if not head or week is None:
                raise MistakeError(f"{path}:{k + 1}: bad hunk header {line.strip()!r}")
            hunk = Hunk(line.strip(), int(head[1]))
            want_old = int(head[2]) if head[2] is not None else 1
            want_new = int(head[4]) if head[4] is not None else 1
            k += 1
            while len(hunk.old) < want_old or len(hunk.new) < want_new:
                if k == len(lines) or lines[k][:1] not in (" ", "-", "+"):
                    raise MistakeError(f"{path}: hunk {hunk.header} ends before its {want_old} old and "
                                       f"{want_new} new lines")
                if lines[k][0] in " -":
                    hunk.old.append(lines[k][1:])
                if lines[k][0] in " +":
                    hunk.new.append(lines[k][1:])
                k += 1
            if (len(hunk.old), len(hunk.new)) != (want_old, want_new):
                raise MistakeError(f"{path}: hunk {hunk.header} does not have {want_old} old and {want_new} "
                                   f"new lines")
            hunks.append(hunk)
        elif line.startswith("# ") and week is None:   # why it aims where it does
            k += 1
        elif line.startswith("\\"):
            raise MistakeError(f"{path}:{k + 1}: files without a final newline are not supported")
        else:
            raise MistakeError(f"{path}:{k + 1}: unexpected line {line.rstrip()!r}")
    if week is None or not all(files.values()):
        raise MistakeError(f"{path}: no hunks")
    return Mistake(why, week, files, aims)


def apply_hunks(text: str, hunks: list[Hunk], where: str) -> str:
    """`text` with the hunks applied in order. Each hunk's old lines must stand at its stated line or, failing
    that, exactly once after the previous hunk; otherwise MistakeError names `where` and the hunk."""
    lines = text.splitlines(keepends=True)
    out: list[str] = []
    pos = 0  # lines of `lines` already consumed
    for hunk in hunks:
        n = len(hunk.old)
        stated = hunk.old_start - 1 if n else hunk.old_start  # a pure insertion names the line before it
        if lines[stated:stated + n] == hunk.old and stated >= pos:
            at = stated
        else:
            found = [i for i in range(pos, len(lines) - n + 1) if lines[i:i + n] == hunk.old]
            if len(found) != 1:
                how = "not found" if not found else f"found {len(found)} times"
                raise MistakeError(f"{where}: hunk {hunk.header} does not apply (its old lines are {how}); "
                                   f"the solution changed: rewrite the mistake against it")
            at = found[0]
        out += lines[pos:at] + hunk.new
        pos = at + n
    return "".join(out + lines[pos:])


def apply_mistake(patch: Path, solutions: Path, into: Path) -> tuple[Mistake, Path]:
    """A fresh copy of `solutions`/weekN at `into` with the mistake of `patch` applied. Every file it changes
    is a regular file of that copy (read_mistake allows plain names only; a link is refused too)."""
    mistake = read_mistake(patch)
    if not (solutions / f"week{mistake.week}").is_dir():
        raise MistakeError(f"{patch}: solutions/week{mistake.week} does not exist")
    shutil.copytree(solutions / f"week{mistake.week}", into, ignore=shutil.ignore_patterns("__pycache__"))
    for file, hunks in mistake.files.items():
        target = into / file
        if target.is_symlink() or not target.is_file() or target.parent != into:
            raise MistakeError(f"{patch}: solutions/week{mistake.week}/{file} is not a file of the solution")
        where = f"{patch.name} on solutions/week{mistake.week}/{file}"
        target.write_text(apply_hunks(target.read_text(encoding="utf-8"), hunks, where), encoding="utf-8")
    return mistake, into
