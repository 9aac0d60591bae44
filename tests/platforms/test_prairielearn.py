"""The PrairieLearn question built by `grade package prairielearn week3`: its info.json, Dockerfile and page,
and its entrypoint run for real against a /grade-like tree (with the venv the Gradescope setup built from
the same wheel), each results.json held to PrairieLearn's documented format (platform_specs)."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import uuid
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import SEED, base_env
from mistakes import ROOT, build
from platform_specs import PL_LIMIT, prairielearn_violations

from grader.platforms.handout import handout_files, leaks
from grader.platforms.prairielearn import HIDDEN_MESSAGE, fit

# week 3's new blocks are in these two files (simiam/course/weeks/week3.py); differential_drive.py and
# quickbot.py hold only earlier weeks' blocks and come from the handout, like go_to_angle.py
EDITED = ("go_to_goal.py", "qb_supervisor.py")


@dataclass
class Question:
    out: Path

    @property
    def image(self) -> Path:
        return self.out / "image"

    @property
    def question(self) -> Path:
        return self.out / "question"


@pytest.fixture(scope="session")
def pl(tmp_path_factory) -> Question:
    from grader.cli import main

    out = tmp_path_factory.mktemp("prairielearn") / "week3"
    assert main(["package", "prairielearn", "week3", "--out", str(out), "--seed", str(SEED),
                 "--image", "course/simiam-week3:2026", "--course", str(ROOT)]) == 0
    return Question(out)


def _entrypoint(pl: Question) -> list[str]:
    return json.loads((pl.question / "info.json").read_text())["externalGradingOptions"]["entrypoint"].split()


def _grade(pl: Question, autograder, tmp_path: Path, fill) -> tuple[str, str]:
    """A /grade-like tree as PrairieLearn lays it out for one job, then the entrypoint of info.json."""
    root = tmp_path / "grade"
    (root / "student").mkdir(parents=True)
    fill(root / "student")
    shared = root / "serverFilesCourse"
    shutil.copytree(pl.out / "serverFilesCourse", shared)
    for path in [shared, *shared.rglob("*")]:          # as a git checkout leaves them: readable by all
        path.chmod(0o755 if path.is_dir() else 0o644)
    command, secret = _entrypoint(pl)
    assert command == "/usr/local/bin/simiam-pl-grade" and secret.startswith("/grade/serverFilesCourse/")
    env = {**base_env(), "GRADE_ROOT": str(root), "SIMIAM_HOME": str(pl.image),
           "SIMIAM_VENV": str(autograder.venv)}
    done = subprocess.run([str(pl.image / "simiam-pl-grade"), str(root) + secret.removeprefix("/grade")],
                          env=env, capture_output=True, text=True, timeout=600)
    locked = root / secret.removeprefix("/grade/")
    assert locked.stat().st_mode & 0o077 == 0 and (locked / "grading.json").stat().st_mode & 0o077 == 0
    assert done.returncode == 0, done.stdout + done.stderr
    return (root / "results" / "results.json").read_text(), done.stdout + done.stderr


def _edited(source: Path):
    """What PrairieLearn's file editors submit: only the files that have an editor."""
    def fill(student: Path) -> None:
        for name in EDITED:
            shutil.copy(source / name, student / name)
    return fill


def test_info_json_enables_external_grading_with_the_image_and_entrypoint(pl: Question):
    info = json.loads((pl.question / "info.json").read_text())
    uuid.UUID(info["uuid"])
    assert info["type"] == "v3" and info["gradingMethod"] == "External"
    options = info["externalGradingOptions"]
    assert options["enabled"] is True and options["image"] == "course/simiam-week3:2026"
    assert 0 < options["timeout"] <= 600
    dockerfile = (pl.image / "Dockerfile").read_text()
    assert re.search(r"^FROM debian:", dockerfile, re.M)
    assert f"ENTRYPOINT {json.dumps(options['entrypoint'].split())}" in dockerfile
    assert f"COPY simiam-pl-grade {options['entrypoint'].split()[0]}" in dockerfile
    assert options["serverFilesCourse"] == ["simiam_week3/"]
    for source in re.findall(r"^COPY (\S+) ", dockerfile, re.M):
        assert (pl.image / source).exists(), f"the Dockerfile copies {source}, which is not in image/"


def test_the_page_has_a_file_editor_with_the_handout_for_each_file_with_blocks(pl: Question):
    page = (pl.question / "question.html").read_text()
    editors = re.findall(r'<pl-file-editor file-name="([^"]+)"[^>]*source-file-name="([^"]+)"', page)
    assert sorted(name for name, _ in editors) == sorted(EDITED)
    handout = handout_files(3, ROOT)
    for name, source in editors:
        assert (pl.question / source).read_text() == handout[name]
    assert "<pl-external-grader-results>" in page
    assert "Some checks are hidden (other goals): make your code" in page  # week 3's own words
    starter = {p.name: p.read_text() for p in (pl.question / "starter").glob("*.py")}
    assert leaks(3, starter, ROOT) == []


def test_the_image_holds_no_secret_the_course_files_do(pl: Question):
    assert not (pl.image / "secret").exists()
    assert not any(str(SEED) in p.read_text(errors="replace") for p in pl.image.rglob("*") if p.is_file())
    secret = json.loads((pl.out / "serverFilesCourse" / "simiam_week3" / "grading.json").read_text())
    assert secret["seed"] == SEED and secret["week"] == 3


@pytest.mark.slow
@pytest.mark.sandbox
def test_correct_code_from_the_editors_scores_one(pl, autograder, tmp_path):
    text, _ = _grade(pl, autograder, tmp_path, _edited(ROOT / "solutions" / "week3"))
    assert prairielearn_violations(text) == []
    results = json.loads(text)
    assert results["gradable"] is True and results["score"] == 1.0
    assert all(t["points"] == t["max_points"] for t in results["tests"])
    assert "isolation: bwrap" in results["message"]
    hidden = [t for t in results["tests"] if t["message"] == HIDDEN_MESSAGE]
    assert len(hidden) == 2
    # the three files without an editor came from the handout, silently: the student could not submit them
    assert "missing from your submission" not in results["message"]


@pytest.mark.slow
@pytest.mark.sandbox
def test_a_wrong_version_loses_exactly_its_points(pl, autograder, tmp_path):
    text, _ = _grade(pl, autograder, tmp_path, _edited(build("wrong", "week3_no_wrap", tmp_path)))
    assert prairielearn_violations(text) == []
    results = json.loads(text)
    lost = {t["name"] for t in results["tests"] if t["points"] < t["max_points"]}
    assert lost == {"week3.go_to_goal.error_wrap"} and results["score"] == pytest.approx(11.5 / 12.5)


@pytest.mark.slow
@pytest.mark.parametrize("upload", ["empty", "not_a_zip"])
def test_an_unreadable_submission_is_not_gradable(pl, autograder, tmp_path, upload):
    def fill(student: Path) -> None:
        if upload == "not_a_zip":
            (student / "week3.zip").write_bytes(b"\x00garbage")
    text, _ = _grade(pl, autograder, tmp_path, fill)
    assert prairielearn_violations(text) == []
    results = json.loads(text)
    assert results["gradable"] is False and results["format_errors"]
    assert "score" not in results


@pytest.mark.slow
@pytest.mark.sandbox
def test_a_hostile_submission_cannot_read_the_secret_nor_forge_the_results(pl, autograder, tmp_path):
    attack = build("attacks/graded", "platform_secret", tmp_path)
    code = (attack / "go_to_goal.py").read_text()
    code = code.replace("__SECRET__", str(tmp_path / "grade" / "serverFilesCourse" / "simiam_week3"))
    (attack / "go_to_goal.py").write_text(code.replace("__RESULTS__", str(tmp_path / "grade" / "results")))
    text, log = _grade(pl, autograder, tmp_path, _edited(attack))
    assert prairielearn_violations(text) == []
    results = json.loads(text)
    theta_g = next(t for t in results["tests"] if t["name"] == "week3.go_to_goal.theta_g")
    assert theta_g["points"] == 0, "student code read the secret seed"
    assert results["score"] < 1.0 and str(SEED) not in text and str(SEED) not in log


def test_results_are_cut_to_fit_prairielearns_limit():
    huge = {"gradable": True, "score": 0.5, "message": "m", "output": "o" * 3_000_000,
            "tests": [{"name": f"t{i}", "points": 0.0, "max_points": 1.0, "message": "x" * 50_000}
                      for i in range(100)]}
    text = fit(huge)
    assert len(text.encode()) <= PL_LIMIT and prairielearn_violations(text) == []


@pytest.mark.parametrize("broken", [
    {"gradable": True, "score": 1.5},
    {"gradable": False},
    {"score": 0.5, "tests": [{"name": "a", "points": 2.0, "max_points": 1.0}]},
    {"score": 0.5, "tests": [{"points": 1.0, "max_points": 1.0}]},
    "x" * (PL_LIMIT + 1),
], ids=["score-over-one", "no-format-errors", "points-over-max", "no-name", "too-big"])
def test_the_spec_validator_catches_what_prairielearn_rejects(broken):
    text = broken if isinstance(broken, str) else json.dumps(broken)
    assert prairielearn_violations(text)
