"""Shared helpers of the sandbox tests: attack submissions, the honest answer, calling the test probes.

(A uniquely named module, not conftest: several test folders have a conftest.py, and `from conftest import`
would pick whichever was imported first.)
"""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

from grader.sandbox.limits import Limits
from grader.sandbox.session import StudentSession

ATTACKS = Path(__file__).resolve().parents[1] / "data" / "attacks"
PROBES = Path(__file__).resolve().parent / "probe_fixture"
LIMITS = Limits(call_seconds=1.5, start_seconds=15.0, total_seconds=30.0)
R, L = 0.0325, 0.09925
HONEST = [(2 * 0.1 + 0.5 * L) / (2 * R), (2 * 0.1 - 0.5 * L) / (2 * R)]
AS_ROOT = os.geteuid() == 0


def make_submission(base: Path, attack: str) -> Path:
    """The honest week-1 files with the attack's files laid over them, readable by the worker's uid."""
    folder = base / f"sub-{attack}"
    folder.mkdir(parents=True)
    for source in (ATTACKS / "_honest", ATTACKS / attack):
        for file in source.glob("*.py"):
            shutil.copy(file, folder / file.name)
    for path in (folder, *folder.iterdir()):
        path.chmod(0o755 if path.is_dir() else 0o644)
    return folder


def graded_attack(base: Path, name: str, **fill: object) -> Path:
    """solutions/week2 with tests/data/attacks/graded/<name>.patch applied; __KEY__ placeholders filled in."""
    import mistakes

    folder = mistakes.build("attacks/graded", name, base, 2)
    for file in mistakes.read_mistake(mistakes.mistake_path("attacks/graded", name)).files:
        text = (folder / file).read_text()
        for key, value in fill.items():
            text = text.replace(f"__{key.upper()}__", str(value))
        (folder / file).write_text(text)
    return folder


def attack(session: StudentSession, fn: str = "attack", timeout: float | None = None, **args):
    """Run the attack function of the submission through the test probe."""
    return session.call("probe", timeout=timeout, name="attack", args={"fn": fn, **args})


def honest_probe(session: StudentSession):
    return session.call("probe", name="uni_to_diff", args={"v": 0.1, "w": 0.5})


def says_it_reads(note: str, name: str) -> bool:
    """Whether a subprocess isolation note says the worker can read the course files called `name` (its
    parenthesis after "can read what its user can read": "(X and Y included)", "(not X or Y, which ...)")."""
    return re.search(re.escape(name) + r"[^;()]*included", note) is not None


def open_marker(folder: Path) -> Path:
    """A file any uid can read, so that a reading attack always has something to return."""
    marker = folder / "marker.txt"
    marker.write_text("open")
    marker.chmod(0o644)
    return marker
