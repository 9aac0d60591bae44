"""Wrong versions kept as mistakes: a unified diff against solutions/weekN, applied to a fresh copy per test.

`tests/data/<kind>/<name>.patch` (a kind of KINDS below) is in the format of
grader.platforms.wrong_versions: a `# <name>: what the mistake is` line, an optional `# aims:` line, then a
unified diff against solutions/weekN, applied strictly.
A `tests/data/<kind>/<name>/` folder instead holds hand-written files laid over the solution as they are.
"""

from __future__ import annotations

import shutil
from pathlib import Path

# The format, the parser and the strict applier live with `grade selfcheck`, which applies the course's
# wrong versions too; this module finds the tests' mistakes and builds them.
from grader.platforms.wrong_versions import (  # noqa: F401 (re-exported for the tests)
    Hunk,
    Mistake,
    MistakeError,
    apply_hunks,
    apply_mistake,
    read_mistake,
)

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
KINDS = ("wrong", "submissions", "stuck", "attacks/graded")


def mistake_path(kind: str, name: str) -> Path:
    return DATA / kind / f"{name}.patch"


def build(kind: str, name: str, into: Path, week: int | None = None, folder_name: str | None = None) -> Path:
    """A fresh copy of solutions/weekN at `into/<folder_name or name>` with the mistake `name` of
    tests/data/<kind>/ applied (a `.patch`, or a folder of hand-written files laid over it)."""
    patch = mistake_path(kind, name)
    mistake = read_mistake(patch) if patch.exists() else None
    if mistake is not None:
        if week is not None and week != mistake.week:
            raise MistakeError(f"{patch}: it changes solutions/week{mistake.week}, not week {week}")
        week = mistake.week
    elif week is None or not (DATA / kind / name).is_dir():
        raise MistakeError(f"no {patch.name} (or folder with a week) in tests/data/{kind}")
    folder = into / (folder_name or name)
    if mistake is not None:
        return apply_mistake(patch, ROOT / "solutions", folder)[1]
    shutil.copytree(ROOT / "solutions" / f"week{week}", folder, ignore=shutil.ignore_patterns("__pycache__"))
    for path in (DATA / kind / name).glob("*.py"):
        shutil.copy(path, folder / path.name)
    return folder


def all_mistakes() -> list[tuple[str, str]]:
    """(kind, name) of every `.patch` mistake under tests/data/."""
    return sorted((kind, p.stem) for kind in KINDS for p in (DATA / kind).glob("*.patch"))
