"""Console scripts run in an emulated Windows (tests/data/windows_like/no_posix.py): no POSIX-only piece
in the process or in the workers it starts; PATH holds only an emulated `taskkill` that logs its calls."""

from __future__ import annotations

import stat
import subprocess
import sys
from importlib.metadata import distribution
from pathlib import Path

import grader

DATA = Path(__file__).resolve().parent / "data" / "windows_like"
SHIM = DATA / "no_posix.py"
# the console scripts as this installation's metadata has them (tests/packaging/test_wheel.py: pyproject.toml)
_SCRIPTS = {e.name: e.value for e in distribution("simiam").entry_points if e.group == "console_scripts"}
GRADE, SIMIAM = _SCRIPTS["grade"], _SCRIPTS["simiam"]


class WindowsLike:
    """`run(entry, *args)`: the console script `entry` in the emulation, from `folder` as working folder."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        bin_dir = folder / "bin"
        bin_dir.mkdir(exist_ok=True)
        # taskkill, run by this interpreter (it plays Windows' own tool, so nothing is hidden from it)
        taskkill = bin_dir / "taskkill"
        taskkill.write_text(f"#!{sys.executable}\n" + (DATA / "taskkill").read_text())
        # the interpreter the workers are started with: the real one, through the emulation
        self.launcher = bin_dir / "python-windows-like"
        self.launcher.write_text(f'#!/bin/sh\nexec "{sys.executable}" -I -S -B "{SHIM}" worker "$@"\n')
        for script in (taskkill, self.launcher):
            script.chmod(script.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
        self.taskkill_log = folder / "taskkill.log"
        # cp1252 output, strict: what `grade week3 > log.txt` writes with on Windows
        self.env = {"PATH": str(bin_dir), "HOME": str(folder), "PYTHONIOENCODING": "cp1252",
                    "TASKKILL_LOG": str(self.taskkill_log),
                    "PYTHONPATH": str(Path(grader.__file__).resolve().parents[1]),
                    "SIMIAM_CACHE_DIR": str(folder / "cache")}

    def run(self, entry: str, *args: str, cwd: Path | None = None, timeout: float = 600
            ) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, str(SHIM), "run", str(self.launcher), entry, *args],
                              capture_output=True, text=True, env=self.env, cwd=cwd or self.folder,
                              timeout=timeout)

    def killed(self) -> set[int]:
        """The pids the emulated taskkill has killed so far."""
        if not self.taskkill_log.exists():
            return set()
        return {int(pid) for line in self.taskkill_log.read_text().splitlines() for pid in line.split()[1:]}
