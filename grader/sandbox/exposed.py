"""What the worker can import: the course's student-facing code and the worker's own, nothing trusted.

The worker (and so student code) sees one library folder built from the list below (grader.sandbox.library
shares one, with bytecode, between bubblewrap workers; a plain subprocess gets a copy per session): the robot
view, the supervisor/controller framework and the provided Stop controller (simiam.control), the week
table and the loader (simiam.course), the robot's spec (simiam.robot.quickbot), and the worker's own
package (grader.inside, which imports nothing else of simiam or grader: tests/sandbox/test_inside.py).
Nothing here implements a student block: the physics (simiam.robot.dynamics and the rest of the
simulator), the checks' maths (grader.reference), the checks, the hidden set, the reference controllers
(instructor_tools) and the solutions stay outside. `python -m grader.sandbox.exposed`
lists the files; tests/sandbox/test_exposed.py proves the list imports nothing outside itself.

bubblewrap binds only this folder and hides simiam/ and grader/ wherever an installed copy would be visible
(site-packages, /usr); a plain subprocess gets it first on sys.path, so importing anything else from
simiam or grader fails there too, but the process can still open any file its user can read.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import sys
from pathlib import Path

import grader
import simiam

PACKAGES = ("simiam", "grader")  # the import names the worker's library replaces

EXPOSED: tuple[str, ...] = (
    "simiam/__init__.py",
    "simiam/control/__init__.py",
    "simiam/control/controller.py",
    "simiam/control/local_brain.py",
    "simiam/control/norm.py",
    "simiam/control/pose.py",
    "simiam/control/robot_view.py",
    "simiam/control/stop.py",
    "simiam/control/supervisor.py",
    "simiam/course/__init__.py",
    "simiam/course/loader.py",
    "simiam/course/placeholders.py",
    "simiam/course/week.py",
    "simiam/course/weeks/__init__.py",
    *sorted(f"simiam/course/weeks/{p.name}"  # every declared week (adding a week is adding a file)
            for p in (Path(simiam.__file__).parent / "course" / "weeks").glob("week*.py")),
    "simiam/laps.py",                  # week 6's declaration holds its lap gate (no student block)
    "simiam/names.py",                 # "did you mean": a misspelt setting, state or event name
    "simiam/numerics.py",              # simiam's import pins the numeric environment; the worker reports it
    "simiam/robot/__init__.py",
    "simiam/robot/quickbot.py",
    "simiam/signals.py",               # LocalBrain reads the debug signals with it
    "grader/__init__.py",
    "grader/inside/__init__.py",       # the worker's own package: imports nothing trusted (grader/inside/)
    "grader/inside/answer_bounds.py",
    "grader/inside/caps.py",
    "grader/inside/probes.py",
    "grader/inside/probes_week2.py",
    "grader/inside/probes_week3.py",
    "grader/inside/probes_week4.py",
    "grader/inside/probes_week5.py",
    "grader/inside/probes_week6.py",
    "grader/inside/probes_week7.py",
    "grader/inside/probing.py",
    "grader/inside/protocol.py",
    "grader/inside/record_codec.py",
    "grader/inside/record_writer.py",
    "grader/inside/rlimits.py",
    "grader/inside/seccomp.py",
    "grader/inside/shorten.py",
    "grader/inside/step_record.py",
    "grader/inside/worker.py",
    "grader/inside/worker_loop.py",
)
WORKER = "grader/inside/worker.py"


def source_of(relative: str) -> Path:
    """Where an exposed file lives in this installation (checkout or site-packages)."""
    return _installed_at(relative.split("/", 1)[0]) / relative


@functools.cache
def _installed_at(package: str) -> Path:
    """The folder holding the imported `package` (resolved once: every worker start reads every file)."""
    top = {"simiam": simiam, "grader": grader}[package]
    if top.__file__ is None:  # a namespace package: some other folder named simiam or grader won
        raise RuntimeError(f"{top.__name__} is imported from {list(top.__path__)}, not from the installed "
                           "package: run from a folder without a stray one")
    return Path(top.__file__).resolve().parent.parent


def build_library(into: Path) -> Path:
    """Copy the exposed files into `into` (created), readable by any uid; return `into`."""
    write_library(into, {relative: source_of(relative).read_bytes() for relative in EXPOSED})
    return into


def write_library(into: Path, sources: dict[str, bytes], *, bytecode: bool = False) -> None:
    """Write `sources` (relative path -> bytes) into `into`, every folder and file readable by any uid
    (the worker runs as another one). With `bytecode`, a checked-hash .pyc beside each source: Python
    re-reads the source and checks its hash before it uses one (grader.sandbox.library)."""
    if bytecode:
        import py_compile  # only when a shared library is built: not on every grading process's import
    for relative, data in sources.items():
        target = into / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
        if bytecode:
            py_compile.compile(str(target), cfile=bytecode_of(target), doraise=True, optimize=0,
                               invalidation_mode=py_compile.PycInvalidationMode.CHECKED_HASH)
    for folder, _dirs, files in os.walk(into):
        os.chmod(folder, 0o755)
        for name in files:
            os.chmod(os.path.join(folder, name), 0o644)


def bytecode_of(source: Path | str) -> str:
    """Where a worker without -O looks for the bytecode of `source`."""
    return importlib.util.cache_from_source(str(source), optimization="")


def installed_copies(paths: list[str]) -> list[str]:
    """simiam/ and grader/ folders inside the import paths the worker keeps (site-packages): the real
    packages, which bubblewrap must hide behind an empty folder."""
    found = []
    for path in paths:
        for name in (*PACKAGES, "instructor_tools"):
            candidate = Path(path) / name
            if candidate.is_dir():
                found.append(str(candidate))
    return found


if __name__ == "__main__":
    print("\n".join(EXPOSED))
    sys.exit(0)
