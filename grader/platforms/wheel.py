"""Build the package wheel a bundle installs, from the instructor's checkout (`pip wheel --no-deps`).

The wheel is what students could install too, so it must hold no answers (issue 11 makes that so).
`answers_in` lists what in a wheel would give answers away, so the build can say so before shipping it.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path


class WheelBuildFailed(RuntimeError):
    """pip could not build the wheel; the message carries pip's last lines."""


# Left by earlier builds and tools: setuptools reuses build/lib, so a file removed from the package (a hidden
# set that moved out) would still ship from there. The wheel is built from a copy without them.
_NOT_SOURCE = ("build", "dist", "*.egg-info", ".venv", "venv", "__pycache__", ".git", ".pytest_cache",
               ".hypothesis", ".ruff_cache", "reports", "runs", "node_modules")


def build_wheel(course: Path, into: Path) -> Path:
    """Build the simiam wheel of `course` (from a clean copy of it) into the folder `into`; return it."""
    into.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="simiam-wheel-") as tmp:
        source = Path(tmp) / "source"
        shutil.copytree(course, source, ignore=shutil.ignore_patterns(*_NOT_SOURCE), symlinks=True)
        wheels = Path(tmp) / "wheels"
        done = subprocess.run(
            [sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "--wheel-dir", str(wheels),
             str(source)], capture_output=True, text=True)
        built = sorted(wheels.glob("simiam-*.whl"))
        if done.returncode != 0 or len(built) != 1:
            tail = "\n".join((done.stderr or done.stdout).strip().splitlines()[-15:])
            raise WheelBuildFailed(f"pip wheel --no-deps {course} failed:\n{tail}")
        target = into / built[0].name
        target.write_bytes(built[0].read_bytes())
    return target


def answers_in(wheel: Path) -> list[str]:
    """Files of `wheel` that hold answers: reference solutions or the instructor's hidden variant sets."""
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
    return [n for n in names if n.startswith(("solutions/", "instructor_tools/")) or "/solutions/" in n
            or (n.startswith("grader/hidden/") and n.endswith(".json"))]
