"""`grade handout weekN --out DIR`: what students download for a week, as a folder and as a zip.

The week's files are generated from solutions/ by the course's stub generator (the blocks new that week
become placeholders, earlier weeks' blocks ship filled, as the course did), plus the week's README. Before
anything is written the handout is checked: no file or block of a later week, no solution code of the
week's own blocks anywhere in it (README included). A leak stops the command; nothing is written.
The release also carries the week's practice set (grader/practice/weekN.json, as `practice_variants.json`):
the variants `grade weekN --practice` runs, which the installed package holds too; never the hidden set.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from grader.platforms.archive import write_zip
from simiam.course.blocks import find_blocks
from simiam.course.weeks import placeholder_for

# Solution lines shorter than this are too generic to call a leak ("return v, w", "pass").
_MIN_LEAK_CHARS = 16


class HandoutLeak(RuntimeError):
    """The handout would give away solution code or later weeks' material; nothing was written."""


def handout_files(week: int, course: Path) -> dict[str, str]:
    """{file name: text} of the week's handout, generated from `course`/solutions."""
    from simiam.course.stubs import generate

    prefix = f"assignments/week{week}/"
    generated = generate(course / "solutions").files
    files = {k[len(prefix):]: v for k, v in generated.items() if k.startswith(prefix)}
    if not files:
        raise ValueError(f"the course has no solutions/week{week} to build week {week}'s handout from")
    readme = course / "assignments" / f"week{week}" / "README.md"
    if not readme.is_file():
        raise ValueError(f"{readme} is missing: every week's handout carries its README")
    files["README.md"] = readme.read_text(encoding="utf-8")
    return files


def leaks(week: int, files: dict[str, str], course: Path) -> list[str]:
    """What in `files` must not reach students in week `week`: later weeks' files and blocks, and any
    line of the reference code of the week's own blocks. Empty when the handout is clean."""
    found: list[str] = []
    own = {p.name for p in (course / "solutions" / f"week{week}").glob("*.py")}
    later: set[str] = set()
    for folder in sorted((course / "solutions").glob("week*")):
        number = folder.name.removeprefix("week")
        if number.isdigit() and int(number) > week:
            later.update(p.name for p in folder.glob("*.py") if p.name not in own)
    for name in files:
        if name in later:
            found.append(f"{name} belongs to a later week")
    secrets = _reference_lines(week, own, course)
    for name, text in files.items():
        if name.endswith(".py"):
            for block in find_blocks(text, name):
                spec = (placeholder_for(name, block.scope, block.occurrence, week)
                        or placeholder_for(name, block.scope, block.occurrence))
                if spec is None or spec.week > week:
                    found.append(f"{name}: block {block.describe()} is not a block of weeks 1..{week}")
                elif spec.week == week and block.body != spec.body(block.indent):
                    found.append(f"{name}: block {block.describe()} is new this week but is not its "
                                 "placeholder")
        lines = {ln.strip() for ln in text.splitlines()}
        found += [f"{name} contains the solution line {s!r}" for s in sorted(secrets & lines)]
    for name in sorted(later):
        stem = name.removesuffix(".py")
        found += [f"{n} mentions {name} (a later week's file)" for n, t in files.items() if stem in t]
    return found


def _reference_lines(week: int, own: set[str], course: Path) -> set[str]:
    """Distinctive lines of the reference code of the blocks new in `week`, minus what the course gives
    away anyway (provided code around the blocks, the placeholders' own lines)."""
    reference: set[str] = set()
    given: set[str] = set()
    for name in sorted(own):
        solution = (course / "solutions" / f"week{week}" / name).read_text(encoding="utf-8")
        inside: set[int] = set()
        for block in find_blocks(solution, name):
            inside.update(range(block.start_line, block.end_line + 1))
            spec = placeholder_for(name, block.scope, block.occurrence, week)
            if spec is not None and spec.week == week:
                reference.update(ln.strip() for ln in block.body.splitlines())
                given.update(ln.strip() for ln in spec.body(block.indent).splitlines())
            elif spec is not None:  # an earlier week's block: the handout ships it filled in
                given.update(ln.strip() for ln in block.body.splitlines())
        given.update(ln.strip() for n, ln in enumerate(solution.splitlines(), 1) if n not in inside)
    return {ln for ln in reference - given if len(ln) >= _MIN_LEAK_CHARS and not ln.startswith("#")}


PRACTICE_FILE = "practice_variants.json"


def practice_file(week: int) -> dict[str, str]:
    """{PRACTICE_FILE: text} of the week's practice set as this grader ships it, or {} without one."""
    from grader.practice import PRACTICE_DIR

    path = PRACTICE_DIR / f"week{int(week)}.json"
    return {PRACTICE_FILE: path.read_text(encoding="utf-8")} if path.is_file() else {}


def build_handout(week: int, out: Path, course: Path) -> tuple[Path, Path]:
    """Write `out`/weekN/ and `out`/weekN.zip (its files under weekN/); return both paths.

    Refuses (ValueError) when `out`/weekN already exists, and raises HandoutLeak without writing anything
    when the check above finds a leak."""
    files = handout_files(week, course)
    problems = leaks(week, files, course)
    if problems:
        raise HandoutLeak(f"week {week}'s handout would leak: " + "; ".join(problems))
    files.update(practice_file(week))
    folder, archive = out / f"week{week}", out / f"week{week}.zip"
    if folder.exists() or folder.is_symlink():  # a dangling link too: the folder is never moved onto one
        raise ValueError(f"{folder} already exists: remove it or choose another --out")
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix=f".week{week}-", dir=out) as tmp:
        staged = Path(tmp) / folder.name
        staged.mkdir()
        for name, text in files.items():
            (staged / name).write_text(text, encoding="utf-8")
        staged.rename(folder)
    write_zip(archive, {f"week{week}/{n}": t.encode("utf-8") for n, t in files.items()})
    return folder, archive


def copy_handout(week: int, course: Path, into: Path) -> Path:
    """The week's handout files (checked) in `into`, for a package that embeds them; returns `into`."""
    files = handout_files(week, course)
    problems = leaks(week, files, course)
    if problems:
        raise HandoutLeak(f"week {week}'s handout would leak: " + "; ".join(problems))
    into.mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (into / name).write_text(text, encoding="utf-8")
    return into

