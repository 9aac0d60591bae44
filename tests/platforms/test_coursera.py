"""The Coursera grader built by `grade package coursera week3`: its build folder, and its entrypoint run for
real on the uploads the Gradescope test uses (reference solution, handout, a wrong version, a syntax error, a
zip with a top folder, a broken zip). The entrypoint is parameterised by a root, not run in Docker:
COURSERA_SHARED points it at a temporary folder laid out like Coursera's /shared (submission/ read-only,
partId in the environment), SIMIAM_HOME at the build folder and SIMIAM_VENV at the venv the Gradescope
setup built from the same wheel. Each feedback is held to Coursera's contract (coursera_spec) and searched
for the seed and the hidden goals."""

from __future__ import annotations

import json
import re
import shutil
import stat
import subprocess
import zipfile
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import SEED, base_env
from coursera_spec import coursera_violations
from mistakes import ROOT, build

from grader.checks.week3 import TRACKING_TURN, seeded_goals, seeded_start_and_goal, tracking_excluded
from grader.platforms.coursera import feedback
from grader.platforms.handout import handout_files, leaks

PART = "simW3"
# week 3's hidden checks drive to goals drawn from the seed (the third from a start away from the origin);
# the way the checks write them
HIDDEN_GOALS = [f"({x:g}, {y:g})" for x, y in [*seeded_goals(SEED, 2, "hidden"),
                                                seeded_start_and_goal(SEED, "hidden")[1],
                                                *seeded_goals(SEED, 1, "tracking", TRACKING_TURN,
                                                              tracking_excluded())]]


@dataclass
class Graded:
    feedback: dict
    page: str
    log: str


@pytest.fixture(scope="session")
def coursera(tmp_path_factory) -> Path:
    from grader.cli import main

    out = tmp_path_factory.mktemp("coursera") / "week3"
    assert main(["package", "coursera", "week3", "--out", str(out), "--seed", str(SEED), "--part-id", PART,
                 "--course", str(ROOT)]) == 0
    return out


def _grade(coursera: Path, autograder, tmp_path: Path, fill, part: str = PART) -> Graded:
    """A /shared-like folder as Coursera lays it out for one submission, then the image's entrypoint."""
    shared = tmp_path / "shared"
    (shared / "submission").mkdir(parents=True)
    fill(shared / "submission")
    for path in [shared / "submission", *(shared / "submission").rglob("*")]:   # read-only, as on Coursera
        path.chmod(0o555 if path.is_dir() else 0o444)
    env = {**base_env(), "COURSERA_SHARED": str(shared), "SIMIAM_HOME": str(coursera),
           "SIMIAM_VENV": str(autograder.venv), "partId": part}
    done = subprocess.run([str(coursera / "simiam-coursera-grade")], env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0 and done.stdout == "", done.stdout + done.stderr   # stdout: nothing at all
    assert coursera_violations(shared) == []
    page = (shared / "htmlFeedback.html").read_text() if (shared / "htmlFeedback.html").exists() else ""
    graded = Graded(json.loads((shared / "feedback.json").read_text()), page, done.stderr)
    shown = json.dumps(graded.feedback) + page
    assert str(SEED) not in shown and str(SEED) not in graded.log
    assert not [g for g in HIDDEN_GOALS if g in shown], "a hidden goal is in the feedback"
    return graded


def _loose(source: Path):
    def fill(folder: Path) -> None:
        for path in sorted(source.glob("*.py")):
            shutil.copy(path, folder / path.name)
    return fill


def test_the_build_folder_is_what_the_dockerfile_needs_and_the_secret_is_the_graders(coursera: Path):
    dockerfile = (coursera / "Dockerfile").read_text()
    assert re.search(r"^FROM debian:", dockerfile, re.M)
    for source in re.findall(r"^COPY (?:--chown=\S+ )?(\S+) ", dockerfile, re.M):
        assert (coursera / source).exists(), f"the Dockerfile copies {source}, which is not in the folder"
    assert 'ENTRYPOINT ["/usr/local/bin/simiam-coursera-grade"]' in dockerfile
    user = re.findall(r"^USER (\S+)", dockerfile, re.M)
    assert user == ["simiam-grader"], "Coursera runs graders without root; the secret must be this user's"
    assert "COPY --chown=simiam-grader:simiam-grader secret/ /opt/simiam/secret/" in dockerfile
    secret = coursera / "secret"
    assert stat.S_IMODE(secret.stat().st_mode) == 0o700
    assert stat.S_IMODE((secret / "grading.json").stat().st_mode) == 0o600
    assert json.loads((secret / "grading.json").read_text())["seed"] == SEED
    outside = [p for p in coursera.rglob("*") if p.is_file() and secret not in p.parents]
    assert not [p for p in outside if str(SEED).encode() in p.read_bytes()], "the seed outside secret/"
    config = json.loads((coursera / "config.json").read_text())
    assert config["week"] == 3 and config["coursera_part_id"] == PART and config["hidden_checks"] == 2
    assert [p.name for p in (coursera / "dist").iterdir()] == [config["wheel"]]
    handout = {p.name: p.read_text() for p in (coursera / "handout").iterdir()}
    assert handout == handout_files(3, ROOT) and leaks(3, handout, ROOT) == []
    assert not [p for p in outside if p.suffix == ".py" and p.parent.name != "handout"]


@pytest.mark.slow
@pytest.mark.sandbox
def test_the_reference_solution_gets_full_marks(coursera, autograder, tmp_path):
    graded = _grade(coursera, autograder, tmp_path, _loose(ROOT / "solutions" / "week3"))
    assert graded.feedback["fractionalScore"] == 1.0 and graded.feedback["feedbackType"] == "HTML"
    assert graded.feedback["feedback"].startswith("Week 3: 12.5 / 12.5 points")
    assert graded.page.count("<tr><td>ok</td>") == 14 and "FAILED" not in graded.page
    assert "2 of the checks are hidden (other goals)" in graded.page and "isolation: bwrap" in graded.page
    # the hidden checks are listed with their points, their message withheld
    assert "reach goals drawn per seed" in graded.page and "its details are not shown" in graded.page


@pytest.mark.slow
@pytest.mark.sandbox
def test_a_zip_with_a_top_folder_gets_full_marks(coursera, autograder, tmp_path):
    def upload(folder: Path) -> None:
        with zipfile.ZipFile(folder / "my-week3.zip", "w") as archive:
            for path in sorted((ROOT / "solutions" / "week3").glob("*.py")):
                archive.write(path, f"week3/{path.name}")
    assert _grade(coursera, autograder, tmp_path, upload).feedback["fractionalScore"] == 1.0


@pytest.mark.slow
@pytest.mark.sandbox
def test_the_untouched_handout_scores_zero(coursera, autograder, tmp_path):
    graded = _grade(coursera, autograder, tmp_path, _loose(coursera / "handout"))
    assert graded.feedback["fractionalScore"] == 0.0
    assert "<tr><td>ok</td>" not in graded.page and "FAILED" in graded.page


@pytest.mark.slow
@pytest.mark.sandbox
def test_a_wrong_version_loses_exactly_its_check(coursera, autograder, tmp_path):
    graded = _grade(coursera, autograder, tmp_path, _loose(build("wrong", "week3_no_wrap", tmp_path)))
    assert graded.feedback["fractionalScore"] == pytest.approx(11.5 / 12.5)
    failed = [ln for ln in graded.feedback["feedback"].splitlines() if ln.startswith("FAILED")]
    assert len(failed) == 1 and "wrapped into [-pi, pi]" in failed[0]
    assert graded.page.count("<tr><td>FAILED</td>") == 1 and "week3.go_to_goal.error_wrap" in graded.page


@pytest.mark.slow
@pytest.mark.sandbox
def test_a_syntax_error_is_named_with_its_file_and_line(coursera, autograder, tmp_path):
    graded = _grade(coursera, autograder, tmp_path,
                    _loose(build("submissions", "loader_syntax_error", tmp_path)))
    failed = [ln for ln in graded.feedback["feedback"].splitlines() if ln.startswith("FAILED")]
    visible = [ln for ln in failed if "its details are not shown" not in ln]
    assert len(failed) - len(visible) == 2       # the hidden checks fail too, without saying more
    assert visible and all(re.search(r"go_to_goal\.py:\d+: syntax error", ln) for ln in visible), visible
    assert 0 < graded.feedback["fractionalScore"] < 1


@pytest.mark.slow
def test_a_broken_zip_gets_zero_and_the_reason(coursera, autograder, tmp_path):
    graded = _grade(coursera, autograder, tmp_path,
                    lambda folder: (folder / "week3.zip").write_bytes(b"PK\x03\x04 not a zip"))
    assert graded.feedback["fractionalScore"] == 0.0
    assert "could not be graded" in graded.feedback["feedback"] and "not a readable zip" in graded.page


@pytest.mark.slow
def test_an_upload_to_another_part_is_not_graded_and_says_where_it_belongs(coursera, autograder, tmp_path):
    graded = _grade(coursera, autograder, tmp_path, _loose(ROOT / "solutions" / "week3"), part="xYz12")
    assert graded.feedback["fractionalScore"] == 0.0
    assert "part simW3" in graded.feedback["feedback"] and "part xYz12" in graded.feedback["feedback"]


@pytest.mark.slow
@pytest.mark.sandbox
def test_a_hostile_submission_cannot_read_the_secret_nor_forge_the_feedback(coursera, autograder, tmp_path):
    attack = build("attacks/graded", "platform_secret", tmp_path)
    code = (attack / "go_to_goal.py").read_text().replace("__SECRET__", str(coursera / "secret"))
    code = code.replace("__RESULTS__/results.json", str(tmp_path / "shared" / "feedback.json"))
    (attack / "go_to_goal.py").write_text(code.replace('"score": 100.0', '"fractionalScore": 1.0'))
    graded = _grade(coursera, autograder, tmp_path, _loose(attack))        # _grade: no seed in the feedback
    theta_g = next(ln for ln in graded.feedback["feedback"].splitlines() if "theta_g: the heading" in ln)
    assert theta_g.startswith("FAILED"), "student code read the secret seed"
    assert graded.feedback["fractionalScore"] < 1.0 and graded.feedback["feedbackType"] == "HTML"


@pytest.mark.slow
def test_a_secret_others_can_read_stops_grading_with_a_grader_error(coursera, autograder, tmp_path):
    secret = coursera / "secret"
    secret.chmod(0o755)
    try:
        graded = _grade(coursera, autograder, tmp_path, _loose(ROOT / "solutions" / "week3"))
    finally:
        secret.chmod(0o700)
    assert graded.feedback["fractionalScore"] == 0.0 and "feedbackType" not in graded.feedback
    assert "grader itself failed, not because of your code" in graded.feedback["feedback"]
    assert "readable by other users" in graded.log            # the reason, for the staff only
    assert "readable by other users" not in graded.feedback["feedback"]


@pytest.mark.slow
@pytest.mark.sandbox
@pytest.mark.skipif(shutil.which("bwrap") is None, reason="bubblewrap makes the container-like namespace")
def test_in_a_container_like_courseras_without_namespaces_grading_refuses(coursera, autograder, tmp_path):
    # bubblewrap lays out what Coursera's container has: the build folder at /opt/simiam, the venv at
    # /opt/simiam-venv, the submission at /shared/submission, no network, and a grader that is not root
    # (uid 1000, owning the secret as simiam-grader does in the image); /dev/null over bwrap stands for a
    # container that forbids user namespaces, so student code runs in a plain subprocess
    shared = tmp_path / "shared"
    (shared / "submission").mkdir(parents=True)
    _loose(ROOT / "solutions" / "week3")(shared / "submission")
    venv = autograder.venv
    base = subprocess.run([str(venv / "bin" / "python"), "-c", "import sys; print(sys.base_prefix)"],
                          capture_output=True, text=True, check=True).stdout.strip()
    system = []
    for top in ("bin", "lib", "lib64", "sbin"):
        path = Path("/") / top
        if path.is_symlink():
            system += ["--symlink", str(path.readlink()), str(path)]
        elif path.is_dir():
            system += ["--ro-bind", str(path), str(path)]
    argv = ["bwrap", "--unshare-user", "--uid", "1000", "--gid", "1000", "--unshare-net", "--unshare-pid",
            "--die-with-parent", "--ro-bind", "/usr", "/usr", *system, "--ro-bind", "/etc", "/etc",
            "--ro-bind", base, base, "--proc", "/proc", "--dev", "/dev", "--tmpfs", "/tmp",
            "--ro-bind", str(coursera), "/opt/simiam", "--ro-bind", str(venv), "/opt/simiam-venv",
            "--bind", str(shared), "/shared", "--ro-bind", "/dev/null", shutil.which("bwrap"),
            "--clearenv", "--setenv", "PATH", "/usr/local/bin:/usr/bin:/bin", "--setenv", "partId", PART,
            "/opt/simiam/simiam-coursera-grade"]
    done = subprocess.run(argv, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0 and done.stdout == "", done.stdout + done.stderr
    assert coursera_violations(shared) == []
    # student code would run as the grader's own uid with nothing between them: official grading fails
    # closed (issue 30 item 4), with what to enable for the staff and no grade for the learner
    result = json.loads((shared / "feedback.json").read_text())
    assert result["fractionalScore"] == 0.0 and not (shared / "htmlFeedback.html").exists()
    assert "not set up to run code safely" in result["feedback"]
    assert "official grading refused: student code would run under the grader's own uid (1000)" in done.stderr
    assert "user namespaces" in done.stderr
    assert str(SEED) not in result["feedback"]


@pytest.mark.slow
@pytest.mark.sandbox
def test_the_hidden_goals_searched_for_are_in_what_the_hidden_checks_report():
    # so that their absence from every feedback above means something: graded here, the hidden checks'
    # own messages name exactly these goals
    from grader.grading import grade_submission

    result = grade_submission(3, ROOT / "solutions" / "week3", seed=SEED, hidden=True)
    said = " ".join(c["message"] for c in result["checks"] if c["visibility"] != "visible")
    assert [g for g in HIDDEN_GOALS if g in said] == HIDDEN_GOALS


def test_hidden_details_stay_out_and_student_text_is_escaped():
    goal = HIDDEN_GOALS[0]
    result = {"week": 3, "score": 1.0, "max_score": 2.0, "status": "graded", "isolation": "bwrap",
              "notices": ["<img src=x onerror=alert(1)>.py was skipped"], "student_output": "</pre><script>",
              "checks": [
                  {"id": "week3.a", "name": "a", "visibility": "visible", "points": 1.0, "max_points": 1.0,
                   "message": "(0, -1) reached & <b>fine</b>"},
                  {"id": "week3.b", "name": "b", "visibility": "hidden", "points": 0.0, "max_points": 1.0,
                   "message": f"{goal} not reached; start pose (0.3, -0.2, 1.1); seed {SEED}"}]}
    payload, page = feedback(result, {"week": 3, "hidden_checks": 1})
    assert payload["fractionalScore"] == 0.5 and payload["feedbackType"] == "HTML"
    for text in (json.dumps(payload), page):
        assert goal not in text and "(0.3, -0.2, 1.1)" not in text and str(SEED) not in text
    assert "(0, -1) reached" in payload["feedback"]                    # visible details are shown
    assert "<img" not in page and "<script>" not in page and "<b>" not in page
    assert "&lt;img src=x onerror=alert(1)&gt;.py was skipped" in page


@pytest.mark.parametrize("broken", [
    {"fractionalScore": 1.5, "feedback": "x"},
    {"fractionalScore": -0.1, "feedback": "x"},
    {"fractionalScore": True, "feedback": "x"},
    {"fractionalScore": 0.5},
    {"fractionalScore": 0.5, "feedback": "x", "feedbackType": "HTML"},   # and no htmlFeedback.html
    {"fractionalScore": 0.5, "feedback": "x", "score": 3},
], ids=["over-one", "negative", "bool", "no-feedback", "html-without-page", "unknown-key"])
def test_the_contract_validator_catches_what_coursera_rejects(broken: dict, tmp_path: Path):
    (tmp_path / "feedback.json").write_text(json.dumps(broken))
    assert coursera_violations(tmp_path)


@pytest.mark.parametrize("part", ["bad id!", "", "x" * 65, "Zb6wb\n"])
def test_a_part_id_coursera_could_not_have_given_stops_the_build_before_anything_is_written(
        part: str, tmp_path: Path, capsys):
    from grader.cli import main

    out = tmp_path / "out"
    assert main(["package", "coursera", "week3", "--out", str(out), "--part-id", part,
                 "--course", str(ROOT)]) == 2
    assert "Coursera part ids are short words" in capsys.readouterr().err and not out.exists()
