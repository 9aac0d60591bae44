"""What a fresh `grade week3` loads: only what grading needs (the speed of issue 15, shown as imports that
must not happen, never as timings), and the version it reports without importlib.metadata."""

from __future__ import annotations

import subprocess
import sys
from importlib import metadata
from pathlib import Path

from grader.result import package_version

ROOT = Path(__file__).resolve().parents[2]


def test_the_reported_version_is_the_installed_distributions():
    """simiam.__version__ is what pyproject.toml builds the distribution with (tool.setuptools.dynamic):
    the result's grader_version and the installed metadata agree."""
    assert package_version() == metadata.version("simiam")


def test_a_fresh_grading_loads_neither_the_stub_generator_nor_importlib_metadata(tmp_path: Path):
    """The skeletons are checked by their stamp (no regeneration: simiam.course.stubs stays unloaded) and
    the version is read from simiam.__version__ (no importlib.metadata, ~30-50 ms of imports)."""
    code = f"""
import sys
from grader.cli import main
code = main(["week3", "--solutions", "--out", {str(tmp_path)!r}])
print(code, sorted(m for m in ("simiam.course.stubs", "importlib.metadata") if m in sys.modules))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines()[-1] == "0 []", out.stdout
    assert (tmp_path / "week3.html").is_file()
