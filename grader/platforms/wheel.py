"""Build the package wheel a bundle installs, from the instructor's checkout (`pip wheel --no-deps`).

The wheel is what students could install too, so it must hold no answers (issue 11 makes that so).
`answers_in` lists what in a wheel would give answers away, so the build can say so before shipping it.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path


class WheelBuildFailed(RuntimeError):
    """pip could not build the wheel; the message carries pip's last lines."""


def build_wheel(course: Path, into: Path) -> Path:
    """Build the simiam wheel of `course` into the folder `into` and return its path."""
    into.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="simiam-wheel-") as tmp:
        done = subprocess.run(
            [sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "--wheel-dir", tmp, str(course)],
            capture_output=True, text=True)
        built = sorted(Path(tmp).glob("simiam-*.whl"))
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
    return [n for n in names if n.startswith("solutions/") or "/solutions/" in n
            or (n.startswith("grader/hidden/") and n.endswith(".json"))]
