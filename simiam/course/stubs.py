"""Generate the students' stubs (assignments/weekN) from the reference solutions (solutions/weekN).

Every `.py` file of a week's solutions is copied; the body of each block that is *new that week*
(simiam.course.placeholders) is replaced by its placeholder, and the blocks of earlier weeks ship filled,
as the course did: that is assignments/weekN, what students receive. simiam/course/skeletons/weekN gets the
same files with *every* block a placeholder (package data: the pristine skeletons the grader splices into;
they ship in the wheel, so they hold no solution code of any week). The generator also writes
`simiam/course/shipped_blocks.py`, the list of blocks each week ships with a fingerprint of each shipped
body: `simiam migrate` reads it (students have no solutions); and the skeletons' stamp
(simiam/course/skeleton_stamp.py), with which the grader checks them against solutions/ cheaply.

    python -m simiam.course.stubs            # regenerate assignments/, the skeletons and shipped_blocks.py
    python -m simiam.course.stubs --check    # exit 1 if the committed files differ from what it generates
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass
from pathlib import Path

from simiam import safe_write
from simiam.course.blocks import BlockError, find_blocks, fingerprint, replace_bodies
from simiam.course.skeleton_stamp import SKELETONS, STAMP, stamp_text
from simiam.course.weeks import get_week, placeholder_for, week_numbers

ROOT = Path(__file__).resolve().parents[2]
MANIFEST = Path(__file__).with_name("shipped_blocks.py")
ASSIGNMENTS = "assignments/week{week}"
# Every folder the generator owns: stale .py files in them are reported (--check) and removed (write).
STUB_FOLDERS = (ASSIGNMENTS, str(SKELETONS.relative_to(ROOT)) + "/week{week}")
_SKIP = {"__pycache__", ".pytest_cache"}


@dataclass(frozen=True)
class Generated:
    """Everything the generator writes: {relative path: text}."""

    files: dict[str, str]


def stub_text(week: int, solution_text: str, file: str, every_block: bool = False) -> tuple[str, list[dict]]:
    """The stub of one solution file for `week`, and the manifest rows of its blocks.

    With `every_block`, earlier weeks' blocks are placeholders too: the packaged skeleton, which holds no
    solution code of any week (a week-2 student has the whole package)."""
    blocks = find_blocks(solution_text, file)
    bodies: dict[int, str] = {}
    rows = []
    for b in blocks:
        # (a block of a later week only: the lookup without the week finds it, to say so below)
        spec = placeholder_for(file, b.scope, b.occurrence, week) or placeholder_for(
            file, b.scope, b.occurrence)
        if spec is None:
            raise BlockError(
                file,
                b.start_line,
                f"week {week}: block {b.describe()} has no entry in "
                "simiam/course/placeholders.py (which week is it new in?)",
            )
        if b.week is not None and b.week != spec.week:
            raise BlockError(
                file, b.start_line, f"the START tag says week {b.week}, placeholders.py says week {spec.week}"
            )
        if spec.week > week:
            raise BlockError(
                file,
                b.start_line,
                f"week {week} ships block {b.describe()}, which placeholders.py "
                f"says is new in week {spec.week}",
            )
        shipped = b.body
        if spec.week == week:
            shipped = bodies[b.ordinal] = spec.body(b.indent)
        elif every_block:
            bodies[b.ordinal] = spec.body(b.indent)
        rows.append(
            {
                "scope": b.scope,
                "occurrence": b.occurrence,
                "week": spec.week,
                "line": b.start_line,
                "shipped": fingerprint(shipped),
            }
        )
    return replace_bodies(solution_text, blocks, bodies), rows


def generate(solutions: Path = ROOT / "solutions") -> Generated:
    """The stubs of every declared week (paths relative to the repository root) and the manifest.
    A BlockError names a declared week whose solutions folder lacks one of its student files."""
    files: dict[str, str] = {}
    manifest: dict[int, dict[str, list[dict]]] = {}
    read: dict[str, bytes] = {}       # the stamp's inputs and outputs, as "weekN/file.py"
    skeletons: dict[str, str] = {}
    for week in week_numbers():
        manifest[week] = {}
        folder = solutions / f"week{week}"
        missing = [name for name in get_week(week).student_files if not (folder / name).is_file()]
        if missing:
            raise BlockError(f"solutions/week{week}", None, f"week {week} declares {', '.join(missing)} "
                             f"(simiam/course/weeks/week{week}.py), which this folder does not have")
        for src in sorted(folder.glob("*.py")):
            read[f"week{week}/{src.name}"] = src.read_bytes()
            solution = src.read_text(encoding="utf-8")
            try:
                text, rows = stub_text(week, solution, src.name)
                for pattern in STUB_FOLDERS:
                    every_block = pattern != ASSIGNMENTS
                    files[f"{pattern.format(week=week)}/{src.name}"] = (
                        stub_text(week, solution, src.name, every_block=True)[0] if every_block else text
                    )
                skeletons[f"week{week}/{src.name}"] = files[f"{STUB_FOLDERS[1].format(week=week)}/{src.name}"]
            except BlockError as e:
                raise BlockError(f"solutions/week{week}/{e.file}", e.line, e.message) from None
            if rows:
                manifest[week][src.name] = rows
    files[str(MANIFEST.relative_to(ROOT))] = _manifest_source(manifest)
    files[str(STAMP.relative_to(ROOT))] = stamp_text(read, skeletons)
    return Generated(files)


def _manifest_source(manifest: dict[int, dict[str, list[dict]]]) -> str:
    out = [
        '"""Generated by `python -m simiam.course.stubs` from solutions/: do not edit by hand.',
        "",
        "SHIPPED[week][file] lists the code blocks that week's stubs ship, in file order, as tuples",
        "(scope, occurrence, week new in, START line, fingerprint of the body as shipped): the fingerprint",
        "(simiam.course.blocks.fingerprint) is that of the placeholder, or of the filled-in code.",
        '"""',
        "",
        "SHIPPED: dict[int, dict[str, list[tuple]]] = {",
    ]
    for week, files in manifest.items():
        if not files:
            out.append(f"    {week}: {{}},")
            continue
        out.append(f"    {week}: {{")
        for file, rows in files.items():
            out.append(f'        "{file}": [')
            for r in rows:
                row = (r["scope"], r["occurrence"], r["week"], r["line"], r["shipped"])
                out.append(f"            {row!r},".replace("'", '"'))
            out.append("        ],")
        out.append("    },")
    out.append("}")
    return "\n".join(out) + "\n"


def differences(generated: Generated, root: Path = ROOT) -> list[str]:
    """Paths whose committed text differs from the generated one, and stale generated stubs."""
    out = [
        p
        for p, text in generated.files.items()
        if not (root / p).is_file() or (root / p).read_text(encoding="utf-8") != text
    ]
    out += [f"{rel} (no longer in solutions/)" for rel in _stale(generated, root)]
    return out


def _stale(generated: Generated, root: Path) -> list[str]:
    """Stub files in the generator's folders that it no longer writes."""
    return [
        str(path.relative_to(root))
        for week in week_numbers()
        for folder in STUB_FOLDERS
        for path in sorted((root / folder.format(week=week)).glob("*.py"))
        if str(path.relative_to(root)) not in generated.files
    ]


def write(generated: Generated, root: Path = ROOT) -> list[str]:
    """Write the generated files under `root`, remove stale stubs; return the paths that changed."""
    changed = differences(generated, root)
    for rel, text in generated.files.items():
        path = root / rel
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            safe_write.write_text(path, text)
    for rel in _stale(generated, root):
        (root / rel).unlink()
    return changed


def main(argv: list[str] | None = None) -> int:
    """`python -m simiam.course.stubs [--check] [--solutions DIR] [--root DIR]`."""
    p = argparse.ArgumentParser(prog="python -m simiam.course.stubs", description=__doc__.splitlines()[0])
    p.add_argument("--check", action="store_true", help="change nothing; exit 1 if the stubs are out of date")
    p.add_argument("--solutions", type=Path, default=ROOT / "solutions")
    p.add_argument(
        "--root", type=Path, default=ROOT, help="where assignments/ is written (default: the repo)"
    )
    args = p.parse_args(argv)
    try:
        generated = generate(args.solutions)
    except BlockError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.check:
        diff = differences(generated, args.root)
        for d in diff:
            print(f"out of date: {d}")
        print("stubs up to date" if not diff else "run `python -m simiam.course.stubs` to regenerate")
        return 1 if diff else 0
    changed = write(generated, args.root)
    print("\n".join(f"wrote {c}" for c in changed) or "nothing changed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
