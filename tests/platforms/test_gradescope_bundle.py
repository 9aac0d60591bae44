"""The Gradescope autograder, built by `grade package gradescope week3`, run for real: unpacked like
/autograder, set up into a fresh venv, and run on a correct, a wrong, a broken and a hostile submission.
Every results.json is held to Gradescope's documented format (platform_specs)."""

from __future__ import annotations

import json
import shutil
import stat
import subprocess
import zipfile
from pathlib import Path

import pytest
from conftest import SEED
from mistakes import ROOT, build
from platform_specs import gradescope_violations

from grader.platforms.gradescope import results_json

pytestmark = [pytest.mark.slow, pytest.mark.sandbox]


def _tests(results: dict) -> dict[str, dict]:
    return {t["name"].split(":", 1)[0]: t for t in results["tests"]}


def test_the_zip_has_the_scripts_at_its_root_and_the_secret_closed(gradescope_zip: Path):
    with zipfile.ZipFile(gradescope_zip) as archive:
        modes = {i.filename: (i.external_attr >> 16) & 0o777 for i in archive.infolist()}
        names = set(modes)
    assert {"setup.sh", "run_autograder", "config.json", "secret/grading.json"} <= names
    assert modes["setup.sh"] == modes["run_autograder"] == 0o755
    assert all(mode == 0o600 for name, mode in modes.items() if name.startswith("secret/"))
    assert [n for n in names if n.startswith("dist/")] == [n for n in names if n.endswith(".whl")]
    # the only Python files are the week's handout (checked for leaks when it is copied in)
    assert not any(n.startswith("solutions") or (n.endswith(".py") and not n.startswith("handout/"))
                   for n in names)
    assert {n for n in names if n.startswith("handout/")} == {
        f"handout/{p.name}" for p in (ROOT / "assignments" / "week3").iterdir() if p.suffix in (".py", ".md")}


def test_setup_installs_the_wheel_and_leaves_the_secret_to_root(autograder):
    source = autograder.root / "source"
    assert stat.S_IMODE((source / "secret").stat().st_mode) == 0o700
    assert stat.S_IMODE((source / "secret" / "grading.json").stat().st_mode) == 0o600
    assert not list(autograder.venv.rglob("hidden/*.json")), "a copy of the hidden set is readable"
    assert not [p for name in ("solutions", "instructor_tools") for p in autograder.venv.rglob(name)]
    pip = subprocess.run([str(autograder.venv / "bin" / "python"), "-m", "pip", "list", "--format=json"],
                         capture_output=True, text=True, check=True)
    assert any(p["name"] == "simiam" for p in json.loads(pip.stdout))
    assert "setup: week 3, 14 checks (2 hidden, shown after_published)" in autograder.setup_output
    assert "setup: isolation " in autograder.setup_output
    site = subprocess.run([str(autograder.venv / "bin" / "python"), "-I", "-c",
                           "import grader, pathlib; print(pathlib.Path(grader.__file__).resolve())"],
                          capture_output=True, text=True, check=True).stdout
    assert site.startswith(str(autograder.venv)), "the bundle must grade with the wheel, not this checkout"
    check = subprocess.run([str(autograder.venv / "bin" / "python"), "-I", "-m", "grader.platforms.official",
                            "--check-installed"], capture_output=True, text=True)
    assert check.returncode == 0, check.stderr


def test_a_correct_zipped_week_folder_gets_full_marks(autograder, tmp_path):
    def upload(folder: Path) -> None:
        with zipfile.ZipFile(folder / "my-week3.zip", "w") as archive:
            for path in sorted((ROOT / "solutions" / "week3").glob("*.py")):
                archive.write(path, f"week3/{path.name}")

    results, log = autograder.grade(upload)
    assert gradescope_violations(results) == []
    assert results["score"] == 12.5 and all(t["status"] == "passed" for t in results["tests"])
    assert all(t["score"] == t["max_score"] for t in results["tests"])
    hidden = [t for t in results["tests"] if t["visibility"] != "visible"]
    assert len(hidden) == 2 and {t["visibility"] for t in hidden} == {"after_published"}
    assert "Isolation (bwrap)" in results["output"] and "graded: 12.5 / 12.5" in log
    assert "2 of the checks are hidden (other goals); you see their results once " \
           "grades are published" in results["output"]
    # the installed wheel grades with the very check set (and hidden set) the bundle was built with
    assert "warning" not in results["extra_data"] and results["extra_data"]["status"] == "graded"


def test_a_wrong_version_loses_exactly_its_check(autograder, tmp_path):
    results, _ = autograder.grade(lambda folder: _loose(build("wrong", "week3_no_wrap", tmp_path), folder))
    assert gradescope_violations(results) == []
    lost = {name for name, t in _tests(results).items() if t["score"] < t["max_score"]}
    assert lost == {"week3.go_to_goal.error_wrap"}
    assert _tests(results)["week3.go_to_goal.error_wrap"]["status"] == "failed"
    assert results["score"] == 11.5


def test_a_broken_upload_gets_zero_and_the_reason(autograder):
    results, _ = autograder.grade(lambda folder: (folder / "week3.zip").write_bytes(b"PK\x03\x04 not a zip"))
    assert gradescope_violations(results) == []
    assert results["score"] == 0 and results["tests"] == []
    assert "could not be graded" in results["output"] and "not a readable zip" in results["output"]


def test_a_syntax_error_is_named_with_its_file_and_line(autograder, tmp_path):
    results, _ = autograder.grade(
        lambda folder: _loose(build("submissions", "loader_syntax_error", tmp_path), folder))
    assert gradescope_violations(results) == []
    failed = [t for t in results["tests"] if t["status"] == "failed"]
    assert failed and all("go_to_goal.py" in t["output"] for t in failed)
    assert 0 < results["score"] < 12.5


def test_a_hostile_submission_cannot_read_the_secret_nor_forge_the_results(autograder, tmp_path):
    attack = build("attacks/graded", "platform_secret", tmp_path)
    code = (attack / "go_to_goal.py").read_text()
    code = code.replace("__SECRET__", str(autograder.root / "source" / "secret"))
    (attack / "go_to_goal.py").write_text(code.replace("__RESULTS__", str(autograder.root / "results")))

    def upload(folder: Path) -> None:
        _loose(attack, folder)
        (folder / "<img src=x onerror=alert(1)>.py").write_text("print('hi')\n")

    results, log = autograder.grade(upload)
    assert gradescope_violations(results) == []
    theta_g = _tests(results)["week3.go_to_goal.theta_g"]
    assert theta_g["status"] == "failed", "student code read the secret seed"
    assert results["score"] < 12.5 and results["tests"]                 # ours, not the forged file
    assert str(SEED) not in json.dumps(results) and str(SEED) not in log
    assert "<img" not in results["output"] and "&lt;img src=x onerror=alert(1)&gt;.py" in results["output"]


def test_an_unlocked_secret_stops_grading_with_a_grader_error(autograder, tmp_path):
    secret = autograder.root / "source" / "secret"
    secret.chmod(0o755)
    try:
        results, log = autograder.grade(lambda folder: _loose(ROOT / "solutions" / "week3", folder))
    finally:
        secret.chmod(0o700)
    assert gradescope_violations(results) == []
    assert results["score"] == 0 and "autograder itself failed" in results["output"]
    assert "readable by other users" in log


@pytest.mark.parametrize("choice", ["hidden", "after_due_date", "visible"])
def test_hidden_checks_get_the_visibility_the_instructor_chose(choice: str):
    result = {"week": 3, "score": 1.0, "max_score": 2.0, "status": "graded", "checks": [
        {"id": "week3.a", "name": "a", "visibility": "visible", "points": 1.0, "max_points": 1.0,
         "status": "passed", "message": "ok"},
        {"id": "week3.b", "name": "b", "visibility": "hidden", "points": 0.0, "max_points": 1.0,
         "status": "failed", "message": "no"}]}
    out = results_json(result, {"week": 3, "hidden_visibility": choice, "hidden_checks": 1}, 1.0)
    assert [t["visibility"] for t in out["tests"]] == ["visible", choice]
    assert gradescope_violations(out) == []


@pytest.mark.parametrize("broken", [
    {"score": 1.0, "tests": [{"name": "a", "score": 1.0, "visibility": "students"}]},
    {"score": float("nan"), "tests": []},
    {"tests": [{"name": "a", "status": "error"}]},
    {"score": 2.0, "tests": [{"name": "a", "score": 1.0}]},
    {"score": 0.0, "output_format": "rtf"},
    {"score": 0.0, "grade": 3},
], ids=["visibility", "nan", "status-and-no-score", "sum", "format", "unknown-key"])
def test_the_spec_validator_catches_what_gradescope_rejects(broken: dict):
    assert gradescope_violations(broken)


def test_a_file_with_nothing_to_write_this_week_may_be_left_out(autograder, tmp_path):
    # week 3 ships differential_drive.py (with week 2's uni_to_diff filled in) and go_to_angle.py complete
    def upload(folder: Path) -> None:
        _loose(ROOT / "solutions" / "week3", folder)
        (folder / "differential_drive.py").unlink()
        (folder / "go_to_angle.py").unlink()

    results, _ = autograder.grade(upload)
    assert gradescope_violations(results) == []
    assert results["score"] == 12.5
    assert "differential_drive.py is missing from your submission" in results["output"]
    assert "the version the course ships was used" in results["output"]


def _loose(source: Path, folder: Path) -> None:
    for path in sorted(source.glob("*.py")):
        shutil.copy(path, folder / path.name)


def test_without_bubblewrap_the_result_says_so_and_the_secret_stays_closed(autograder, tmp_path):
    # an image where bubblewrap is missing: the PATH run_autograder sees has no bwrap
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for tool in ("bash", "mkdir", "env", "printf"):
        found = shutil.which(tool)
        if found:
            (bin_dir / tool).symlink_to(found)
    attack = build("attacks/graded", "platform_secret", tmp_path)
    secret = str(autograder.root / "source" / "secret")
    code = (attack / "go_to_goal.py").read_text().replace("__SECRET__", secret)
    (attack / "go_to_goal.py").write_text(code.replace("__RESULTS__", str(autograder.root / "results")))
    results, log = autograder.grade(lambda folder: _loose(attack, folder), PATH=str(bin_dir))
    assert gradescope_violations(results) == []
    assert "Isolation (subprocess)" in results["output"] and "no bubblewrap" in results["output"]
    assert _tests(results)["week3.go_to_goal.theta_g"]["status"] == "failed", "student code read the secret"
    assert str(SEED) not in json.dumps(results) and str(SEED) not in log
