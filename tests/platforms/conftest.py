"""The built bundles, installed once per session the way the platforms install them.

`autograder` unpacks the week-3 Gradescope zip into a temporary tree laid out like /autograder, runs its
setup.sh into a fresh venv (AUTOGRADER_ROOT and SIMIAM_VENV move the paths; apt is skipped), and grades
submissions through run_autograder. The PrairieLearn tests reuse that venv (the image installs the same
wheel) with GRADE_ROOT / SIMIAM_HOME pointing at a /grade-like tree.

The venv holds only what setup.sh installs from the bundle's wheel: the tests grade with the package a
Gradescope image would have, not with this checkout.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import zipfile
from dataclasses import dataclass
from pathlib import Path

import pytest
from mistakes import ROOT

SEED = 918273645            # distinctive, so that a leak of it is easy to spot in any output


def base_env() -> dict[str, str]:
    """What a platform gives its scripts: a plain PATH, nothing of this test run's environment."""
    return {"PATH": "/usr/local/bin:/usr/bin:/bin", "LANG": "C.UTF-8",
            "HOME": os.environ.get("HOME", "/root")}


def extract(zip_path: Path, into: Path) -> None:
    """Unpack like Gradescope does, keeping the Unix modes stored in the zip."""
    with zipfile.ZipFile(zip_path) as archive:
        for info in archive.infolist():
            target = into / info.filename
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(archive.read(info))
            mode = (info.external_attr >> 16) & 0o777
            if mode:
                target.chmod(mode)


@dataclass
class Autograder:
    root: Path
    venv: Path
    setup_output: str

    def env(self, **extra: str) -> dict[str, str]:
        return {**base_env(), "AUTOGRADER_ROOT": str(self.root), "SIMIAM_VENV": str(self.venv), **extra}

    def grade(self, fill, **env: str) -> tuple[dict, str]:
        """Empty submission/ and results/, let `fill(submission_folder)` upload, run run_autograder (with
        `env` on top of the platform's environment)."""
        for part in ("submission", "results"):
            shutil.rmtree(self.root / part, ignore_errors=True)
            (self.root / part).mkdir()
        fill(self.root / "submission")
        done = subprocess.run([str(self.root / "source" / "run_autograder")], env=self.env(**env),
                              cwd=self.root, capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, done.stdout + done.stderr
        text = (self.root / "results" / "results.json").read_text()
        return json.loads(text), done.stdout + done.stderr


@pytest.fixture(scope="session")
def gradescope_zip(tmp_path_factory) -> Path:
    from grader.cli import main

    out = tmp_path_factory.mktemp("bundle") / "autograder.zip"
    assert main(["package", "gradescope", "week3", "--out", str(out), "--seed", str(SEED),
                 "--course", str(ROOT)]) == 0
    return out


@pytest.fixture(scope="session")
def autograder(gradescope_zip, tmp_path_factory) -> Autograder:
    base = tmp_path_factory.mktemp("gradescope")
    root = base / "autograder"
    (root / "source").mkdir(parents=True)
    extract(gradescope_zip, root / "source")
    ag = Autograder(root, base / "venv", "")
    done = subprocess.run(["bash", str(root / "source" / "setup.sh")], env=ag.env(SIMIAM_SKIP_APT="1"),
                          cwd=root, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout + done.stderr
    ag.setup_output = done.stdout + done.stderr
    return ag
