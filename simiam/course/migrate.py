"""`simiam migrate weekN --from LAST_WEEK [--to THIS_WEEK] [--dry-run]`: carry your blocks forward.

The manual's "How to migrate your solutions from last week", block by block. Each code block of this
week's folder that also existed last week receives the body of your last week's block, re-indented, when
  - you filled it in last week (it is no longer the placeholder, nor the code the course shipped), and
  - the course did not change it this week (placeholders.py `revised_in`), and
  - you have not already edited it in this week's folder (migrate never overwrites your work).
Blocks that are new this week stay as shipped. Blocks are matched by file, enclosing function and position.

All or nothing: if any file is missing, any marker was deleted or duplicated, or any block you would carry
does not parse where it goes, nothing is written and every problem is listed with its file and line.
Files are written through a temporary file and a rename, so none is ever left half-written.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from simiam.course.blocks import Block, BlockError, def_line, find_blocks, fingerprint, replace_bodies
from simiam.course.folders import WeekFolderNotFound, default_week_folder, week_folder
from simiam.course.shipped_blocks import SHIPPED
from simiam.course.splice import check_body, read_submission_file
from simiam.course.weeks import get_week, placeholder_for, previous_week, week_numbers

EXIT_OK, EXIT_REFUSED, EXIT_USAGE = 0, 1, 2


def _shown(path: str | Path) -> str:
    """A path as the student would type it: relative to the current folder when under it (the absolute
    paths of a resolved week folder made every line long)."""
    try:
        return Path(path).relative_to(Path.cwd()).as_posix() or "."
    except ValueError:
        return str(path)


@dataclass
class BlockMove:
    """What happened to one block of this week's folder."""

    file: str  # the path in this week's folder
    block: str  # "GoToGoal.execute (block 2)"
    moved: bool
    why: str
    line: int | None = None  # in this week's file

    def __str__(self) -> str:
        verb = "moved" if self.moved else "kept "
        where = f"{_shown(self.file)}:{self.line}" if self.line else _shown(self.file)
        return f"  {verb}  {where}  {self.block}: {self.why}"


@dataclass
class Migration:
    """The plan (and, unless refused or a dry run, what was written)."""

    week: int
    source: Path
    target: Path
    moves: list[BlockMove] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    errors: list[BlockError] = field(default_factory=list)
    texts: dict[str, str] = field(default_factory=dict)  # new text of each target file that changes
    written: list[str] = field(default_factory=list)

    @property
    def last(self) -> int:
        """Last week: the declared week before this one (they need not be numbered without gaps)."""
        return previous_week(self.week)

    @property
    def refused(self) -> bool:
        return bool(self.errors)

    def report(self, dry_run: bool = False) -> str:
        head = f"simiam migrate week{self.week}: from {_shown(self.source)} into {_shown(self.target)}"
        if self.refused:
            lines = [head, "Refused: nothing was changed. Fix these and run it again:"]
            return "\n".join(lines + [f"  {e}" for e in self.errors])
        moved = sorted(self.texts)
        if not moved:  # one line per reason, not one per block: nothing here asks for a look at each file
            why: dict[str, list[str]] = {}
            for m in self.moves:
                why.setdefault(m.why, []).append(m.block)
            kept = [f"  kept   {reason}: {', '.join(blocks)}" for reason, blocks in why.items()]
            return "\n".join([head, *kept, *(f"  note   {n}" for n in self.notes),
                              "Nothing to carry: this week's folder is left as it is."])
        lines = [head, *map(str, self.moves), *(f"  note   {n}" for n in self.notes)]
        if dry_run:
            lines.append(f"Dry run: would write {', '.join(moved)}; nothing was changed.")
        else:
            lines.append(f"Wrote {', '.join(self.written)}.")
        return "\n".join(lines)


def _blocks(folder: Path, name: str, label: str, errors: list[BlockError]) -> tuple[str, list[Block]] | None:
    path = folder / name
    if not os.path.lexists(path):
        errors.append(BlockError(label, None, f"missing file (expected {name} in {folder})"))
        return None
    try:
        text = read_submission_file(path, label)
        return text, find_blocks(text, label)
    except BlockError as e:
        errors.append(e)
        return None


def _check_layout(
    blocks: list[Block], expected: list[tuple], text: str, label: str, week: int, errors: list[BlockError]
) -> bool:
    """The file's blocks are exactly those week `week` shipped (by scope and count), else errors."""
    want: dict[str, int] = {}
    for scope, *_ in expected:
        want[scope] = want.get(scope, 0) + 1
    got: dict[str, list[Block]] = {}
    for b in blocks:
        got.setdefault(b.scope, []).append(b)
    ok = True
    for scope, n in want.items():
        have = got.get(scope, [])
        if len(have) < n:
            line = have[-1].start_line if have else def_line(text, scope) or None
            errors.append(
                BlockError(
                    label,
                    line,
                    f"{scope} should have {n} code block(s) as week {week} "
                    f"shipped it, found {len(have)} (START/END lines deleted?)",
                )
            )
            ok = False
        elif len(have) > n:
            errors.append(
                BlockError(
                    label,
                    have[n].start_line,
                    f"{scope} has {len(have)} code blocks, week "
                    f"{week} shipped {n} (START/END lines duplicated?)",
                )
            )
            ok = False
    for scope, have in got.items():
        if scope not in want:
            errors.append(
                BlockError(
                    label,
                    have[0].start_line,
                    f"a code block in {scope}, where week {week} "
                    "has none (markers added or the function renamed?)",
                )
            )
            ok = False
    return ok


def plan(week: int, source: Path, target: Path) -> Migration:
    """Work out every block's fate without writing anything."""
    mig = Migration(week, source, target)
    last, this = SHIPPED.get(mig.last, {}), SHIPPED[week]
    sources: dict[str, dict[tuple[str, int], Block] | None] = {}
    for name, rows in this.items():
        label = str(target / name)
        found = _blocks(target, name, label, mig.errors)
        if found is None or not _check_layout(found[1], rows, found[0], label, week, mig.errors):
            continue
        text, blocks = found
        bodies: dict[int, str] = {}
        for t in blocks:
            body = _carry(mig, name, text, blocks, t, sources)
            if body is not None:
                bodies[t.ordinal] = body
        if bodies:
            mig.texts[name] = replace_bodies(text, blocks, bodies)
    for name, rows in last.items():
        here = {(r[0], r[1]) for r in this.get(name, [])}
        for scope, occ, *_ in rows:
            if (scope, occ) not in here:
                mig.notes.append(
                    f"{name} {scope}: not carried, week {week} has no code block there "
                    "(the course provides that code now)"
                )
    return mig


def _source_blocks(mig: Migration, name: str, cache: dict) -> dict[tuple[str, int], Block] | None:
    """Last week's blocks of `name` by key, or None (with the errors listed) if the file is unusable."""
    if name not in cache:
        label = str(mig.source / name)
        found = _blocks(mig.source, name, label, mig.errors)
        expected = SHIPPED[mig.last][name]
        ok = found is not None and _check_layout(
            found[1], expected, found[0], label, mig.last, mig.errors
        )
        cache[name] = {b.key: b for b in found[1]} if ok and found else None
    return cache[name]


def _carry(mig: Migration, name: str, text: str, blocks: list[Block], t: Block, cache: dict) -> str | None:
    """Decide the fate of this week's block `t`: record it in `mig`; return the body to write, if any."""
    week, label = mig.week, str(mig.target / name)
    spec = placeholder_for(name, t.scope, t.occurrence, week)

    def keep(why: str) -> None:
        """Record that the block stays as it is here (no body to write)."""
        mig.moves.append(BlockMove(label, t.describe(), False, why, t.start_line))

    if spec is None or spec.week == week:
        keep("new this week: yours to write")
        return None
    if week in spec.revised_in:
        keep(f"shipped version kept: {spec.revised_why}")
        return None
    last_shipped = {(r[0], r[1]): r[4] for r in SHIPPED[mig.last].get(name, [])}
    if t.key not in last_shipped:
        keep(f"not in week {mig.last}")
        return None
    src = _source_blocks(mig, name, cache)
    if src is None:
        return None  # the errors are listed already
    s = src[t.key]
    body, err = check_body(text, blocks, t, s, str(mig.source / name))
    if err:
        mig.errors.append(err)
        return None
    theirs, here = fingerprint(s.body), fingerprint(t.body)
    shipped_here = {(r[0], r[1]): r[4] for r in SHIPPED[week][name]}[t.key]
    if theirs == fingerprint(spec.body("")):
        keep(f"you had not filled it in week {mig.last} (still the placeholder); shipped version kept")
        return None
    if theirs == last_shipped[t.key]:
        keep(f"same as the course shipped in week {mig.last}; this week's version kept")
        return None
    if theirs == here:
        if here == shipped_here:
            keep("your code is the same as this week's shipped code; nothing to move")
            return None
        keep("already your code (migrated before)")
        return None
    if here != shipped_here:
        mig.errors.append(
            BlockError(
                label,
                t.start_line,
                f"you already changed the block of {t.describe()} in this week's folder; migrate will not "
                "overwrite it (undo that edit, or copy the block by hand)",
            )
        )
        return None
    mig.moves.append(
        BlockMove(
            label, t.describe(), True, f"your code from {mig.source / name}:{s.start_line}", t.start_line
        )
    )
    return body


def write_atomically(folder: Path, texts: dict[str, str]) -> list[str]:
    """Write every file to a temporary file first, then rename them all into place."""
    temps: list[tuple[str, Path]] = []
    try:
        for name, text in texts.items():
            dest = folder / name
            fd, tmp_name = tempfile.mkstemp(prefix=f".{name}.", suffix=".migrate", dir=folder)
            temps.append((name, Path(tmp_name)))
            with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
                f.write(text)
                f.flush()
                os.fsync(f.fileno())
            os.chmod(tmp_name, os.stat(dest).st_mode & 0o777)
        done: list[str] = []
        for name, tmp in temps:
            try:
                os.replace(tmp, folder / name)
            except OSError as e:
                e.strerror = f"{e.strerror} (already replaced: {', '.join(done) or 'none'})"
                raise
            done.append(name)
    finally:
        for _, tmp in temps:
            if tmp.exists():
                tmp.unlink()
    return [name for name, _ in temps]


def migrate(week: int, source: Path, target: Path, dry_run: bool = False) -> Migration:
    """Plan the migration and, unless refused or `dry_run`, write it."""
    mig = plan(week, Path(source), Path(target))
    if not mig.refused and not dry_run and mig.texts:
        mig.written = write_atomically(Path(target), mig.texts)
    return mig


def _source_folder(given: str, last_week: int) -> Path:
    """--from: the folder given; a bare `weekN` that is no folder here is looked for by the default rule
    (./weekN, ./assignments/weekN), so `--from week3` works in the checkout and in a course folder."""
    path = Path(given).expanduser()
    if path.is_dir() or str(given).strip().lower() != f"week{last_week}":
        return path
    try:
        return default_week_folder(last_week)
    except WeekFolderNotFound:
        return path  # reported as "no such folder" with the name the student typed


def main(args: argparse.Namespace) -> int:
    """`simiam migrate` (args: week, source, target, dry_run). Exit 0 done, 1 refused, 2 bad arguments."""
    later = ", ".join(f"week{n}" for n in week_numbers()[1:])
    try:
        week = get_week(args.week).number
    except ValueError:
        week = None
    if week is None or week == week_numbers()[0]:
        print(f"simiam migrate: no week {args.week!r} to migrate into ({later})", file=sys.stderr)
        return EXIT_USAGE
    if week not in SHIPPED or previous_week(week) not in SHIPPED:
        print(f"simiam migrate: the course's list of shipped blocks has no week{week} yet "
              "(instructors: python -m simiam.course.stubs)", file=sys.stderr)
        return EXIT_USAGE
    try:
        source = _source_folder(args.source, previous_week(week))
        target = week_folder(week, args.target)
    except WeekFolderNotFound as exc:
        print(f"simiam migrate: {exc} (--to PATH)", file=sys.stderr)
        return EXIT_USAGE
    for what, folder in (("--from", source), ("--to", target)):
        if not folder.is_dir():
            print(f"simiam migrate: {what} {folder}: no such folder", file=sys.stderr)
            return EXIT_USAGE
    if source.resolve() == target.resolve():
        print("simiam migrate: --from and --to are the same folder", file=sys.stderr)
        return EXIT_USAGE
    try:
        mig = migrate(week, source, target, dry_run=args.dry_run)
    except OSError as e:  # e.g. a read-only folder: fails on the first temporary file, before any rename
        print(f"simiam migrate: could not write into {target}: {e.strerror}", file=sys.stderr)
        return EXIT_REFUSED
    print(mig.report(dry_run=args.dry_run))
    return EXIT_REFUSED if mig.refused else EXIT_OK
