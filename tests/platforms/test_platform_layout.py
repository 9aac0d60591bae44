"""Issue 22, "done means": the week-3 bundles laid out at the platforms' own paths, in a container (see
container.py), and graded there: Gradescope's /autograder with setup.sh run into a fresh /opt/simiam-venv,
then run_autograder; PrairieLearn's image built by replaying its Dockerfile's steps, then a /grade tree per
job and info.json's entrypoint. Each image is built once and run in both kinds of container: one where the
grader's bubblewrap works and one with Docker's default capabilities, where it cannot create namespaces.

Seven uploads each: the reference solution, the handout, a wrong solution, a syntax error, a zip with a top
folder, and the hostile uploads of issue 22 items 6 (print_hidden_goals) and 7 (platform_no_sandbox). Every
results.json is held to the platform's format, and nothing a student sees holds a hidden goal or the seed.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import zipfile
from collections.abc import Callable
from pathlib import Path

import pytest
from conftest import SEED, extract
from container import PYTHON, Container, usable
from mistakes import ROOT, build
from platform_specs import gradescope_violations, prairielearn_violations

from grader.grading import grade_submission
from grader.sandbox.capabilities import OFFICIAL_PARTIAL

pytestmark = [pytest.mark.slow, pytest.mark.sandbox,
              pytest.mark.skipif(bool(usable()), reason=usable() or "containers can be made")]

KINDS = {"bwrap": True, "no-namespaces": False}
SECRET = {"gradescope": "/autograder/source/secret", "prairielearn": "/grade/serverFilesCourse/simiam_week3"}


def _loose(source: Path, folder: Path) -> None:
    for path in sorted(source.glob("*.py")):
        shutil.copy(path, folder / path.name)


def _zipped(folder: Path) -> None:
    with zipfile.ZipFile(folder / "my-week3.zip", "w") as archive:
        for path in sorted((ROOT / "solutions" / "week3").glob("*.py")):
            archive.write(path, f"week3/{path.name}")


def _attack(name: str, platform: str, tmp: Path) -> Callable[[Path], None]:
    def fill(folder: Path) -> None:
        attack = build("attacks/graded", name, tmp / platform)
        code = (attack / "go_to_goal.py").read_text().replace("__SECRET__", SECRET[platform])
        (attack / "go_to_goal.py").write_text(code)
        _loose(attack, folder)
    return fill


UPLOADS = ["reference", "handout", "wrong", "syntax_error", "zip_with_top_folder", "print_hidden_goals",
           "platform_no_sandbox"]


def _upload(name: str, platform: str, tmp: Path) -> Callable[[Path], None]:
    return {"reference": lambda f: _loose(ROOT / "solutions" / "week3", f),
            "handout": lambda f: _loose(ROOT / "assignments" / "week3", f),
            "wrong": lambda f: _loose(build("wrong", "week3_no_wrap", tmp / platform), f),
            "syntax_error": lambda f: _loose(build("submissions", "loader_syntax_error", tmp / platform), f),
            "zip_with_top_folder": _zipped}.get(name) or _attack(name, platform, tmp)


@pytest.fixture(scope="module")
def secrets() -> list[re.Pattern]:
    """What must never be shown: the seed, and each hidden goal (or start pose) of week 3 under SEED, as a
    pair of numbers however it is written: "0.18 -0.54", "(0.18, -0.54)", "[0.18, -0.54]"."""
    result = grade_submission(3, ROOT / "solutions" / "week3", seed=SEED, hidden=True)
    pairs = set()
    for check in result["checks"]:
        if check["visibility"] != "visible":
            for run in check["details"].get("runs") or [check["details"]]:
                pairs.update(tuple(run[key][:2]) for key in ("goal", "start") if run.get(key))
    assert len(pairs) >= 2
    return [re.compile(re.escape(str(SEED)))] + [
        re.compile(rf"(?<![\d.]){re.escape(str(x))}[\s,]+{re.escape(str(y))}(?![\d])") for x, y in pairs]


def _leaks(text: str, secrets: list[re.Pattern]) -> list[str]:
    return [p.pattern for p in secrets if p.search(text)]


@pytest.fixture(scope="module")
def wheelhouse(gradescope_zip, tmp_path_factory) -> Path:
    """The wheel's dependencies, fetched once for both images: their pip installs then read them from here
    (PIP_NO_INDEX, PIP_FIND_LINKS, which setup.sh's and the Dockerfile's pip honour) instead of the index."""
    house = tmp_path_factory.mktemp("wheelhouse")
    with zipfile.ZipFile(gradescope_zip) as archive:
        wheel = next(n for n in archive.namelist() if n.endswith(".whl"))
        (house / Path(wheel).name).write_bytes(archive.read(wheel))
    version = subprocess.run([PYTHON, "-c", "import sys; print('%d.%d' % sys.version_info[:2])"],
                             capture_output=True, text=True, check=True).stdout.strip()
    done = subprocess.run([sys.executable, "-m", "pip", "download", "--quiet", "--only-binary=:all:",
                           "--python-version", version, "--dest", str(house), str(house / Path(wheel).name)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    return house


OFFLINE = {"PIP_NO_INDEX": "1", "PIP_FIND_LINKS": "/wheelhouse"}


# ---- Gradescope ----------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def gradescope_image(gradescope_zip, wheelhouse, tmp_path_factory) -> Path:
    """/autograder/source unpacked and setup.sh run, as Gradescope builds its image (Docker's defaults)."""
    base = tmp_path_factory.mktemp("gs-image")
    (base / "autograder" / "source").mkdir(parents=True)
    (base / "venv").mkdir()
    extract(gradescope_zip, base / "autograder" / "source")
    box = _gs_container(base, namespaces=False)
    box.binds["/wheelhouse"] = wheelhouse
    done = box.run(["bash", "/autograder/source/setup.sh"], {"SIMIAM_SKIP_APT": "1", **OFFLINE})
    assert done.returncode == 0, done.stdout + done.stderr
    assert "setup: isolation subprocess with a dedicated uid (bubblewrap cannot create" in done.stdout
    return base


def _gs_container(base: Path, namespaces: bool) -> Container:
    return Container({"/autograder": base / "autograder", "/opt/simiam-venv": base / "venv"}, namespaces)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("upload", UPLOADS)
def test_gradescope(gradescope_image, secrets, tmp_path, kind, upload):
    root = gradescope_image / "autograder"
    for part in ("submission", "results"):
        shutil.rmtree(root / part, ignore_errors=True)
        (root / part).mkdir()
    _upload(upload, "gradescope", tmp_path)(root / "submission")
    # what Gradescope puts beside them (its mode undocumented; here readable by all): the student's earlier
    # submissions with their whole results, hidden tests' output included
    metadata = root / "submission_metadata.json"
    metadata.write_text(json.dumps({"id": 1, "users": [{"name": "A Student"}], "previous_submissions": [
        {"score": 12.5, "results": {"tests": [{"name": "week3.go_to_goal.other_goals", "visibility":
                                                "after_published", "output": "GOAL 0.18 -0.54"}]}}]}))
    metadata.chmod(0o644)
    done = _gs_container(gradescope_image, KINDS[kind]).run(["/autograder/source/run_autograder"])
    assert done.returncode == 0, done.stdout + done.stderr
    results = json.loads((root / "results" / "results.json").read_text())
    assert gradescope_violations(results) == []
    shown = results["output"] + json.dumps([t for t in results["tests"] if t["visibility"] == "visible"])
    assert _leaks(shown, secrets) == [] and str(SEED) not in json.dumps(results) + done.stdout
    tests = {t["name"].split(":", 1)[0]: t for t in results["tests"]}
    if KINDS[kind]:
        assert "Isolation (bwrap)" in results["output"]
    else:
        assert f"Isolation (subprocess): {OFFICIAL_PARTIAL}: " in results["output"]
        assert "Operation not permitted" in results["output"] and "local check only" not in results["output"]
    _expect(upload, results["score"], {n: t["score"] == t["max_score"] for n, t in tests.items()},
            results["output"] + json.dumps(results["tests"]))


def test_with_the_two_capabilities_the_doc_names_bubblewrap_works(gradescope_image):
    # docs/platforms.md: a container started with Docker's defaults plus SYS_ADMIN and NET_ADMIN (and, on a
    # real Docker, a seccomp profile and AppArmor that allow mounts) runs the full sandbox
    root = gradescope_image / "autograder"
    for part in ("submission", "results"):
        shutil.rmtree(root / part, ignore_errors=True)
        (root / part).mkdir()
    _loose(ROOT / "solutions" / "week3", root / "submission")
    box = _gs_container(gradescope_image, namespaces=False)
    box.extra_caps = ("SYS_ADMIN", "NET_ADMIN")
    done = box.run(["/autograder/source/run_autograder"])
    results = json.loads((root / "results" / "results.json").read_text())
    assert "Isolation (bwrap)" in results["output"] and results["score"] == 12.5, done.stdout


def _expect(upload: str, score: float, passed: dict[str, bool], text: str) -> None:
    """What each upload earns, on either platform (score of 12.5 points)."""
    if upload in ("reference", "zip_with_top_folder", "print_hidden_goals"):
        assert score == pytest.approx(12.5) and all(passed.values()), text[:3000]
    elif upload == "handout":
        assert score < 12.5 and not passed["week3.go_to_goal.theta_g"]
    elif upload == "wrong":
        assert [n for n, ok in passed.items() if not ok] == ["week3.go_to_goal.error_wrap"]
    elif upload == "syntax_error":
        assert 0 < score < 12.5 and "go_to_goal.py" in text
    else:   # platform_no_sandbox: theta_g only if it got out
        assert not passed["week3.go_to_goal.theta_g"] and "escaped: []" in text, text[:3000]


# ---- PrairieLearn --------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def pl_image(wheelhouse, tmp_path_factory) -> Path:
    """The question built, and its image built by replaying the Dockerfile's COPY and RUN steps (all but
    the apt-get one, which installs what the host has) into folders bound at the image's paths."""
    from grader.cli import main

    base = tmp_path_factory.mktemp("pl-image")
    out = base / "package"
    assert main(["package", "prairielearn", "week3", "--out", str(out), "--seed", str(SEED),
                 "--course", str(ROOT)]) == 0
    for folder in ("opt-simiam", "venv", "local-bin"):
        (base / folder).mkdir()
    box = _pl_container(base, None, namespaces=False)
    box.binds["/wheelhouse"] = wheelhouse
    places = {"/opt/simiam/": base / "opt-simiam", "/usr/local/bin/": base / "local-bin"}
    lines = (out / "image" / "Dockerfile").read_text().replace("\\\n", " ").splitlines()
    for line in lines:
        step, _, rest = line.partition(" ")
        if step == "COPY":
            source, target = rest.split()
            prefix = next(p for p in places if target.startswith(p))
            dest = places[prefix] / target[len(prefix):]
            if (out / "image" / source).is_dir():
                shutil.copytree(out / "image" / source, dest)
            else:
                dest = dest / Path(source).name if target.endswith("/") else dest
                dest.parent.mkdir(parents=True, exist_ok=True)
                shutil.copy(out / "image" / source, dest)
        elif step == "RUN" and "apt-get" not in rest:
            done = box.run(["sh", "-c", rest], OFFLINE)
            assert done.returncode == 0, f"{line}\n{done.stdout}{done.stderr}"
    return base


def _pl_container(base: Path, job: Path | None, namespaces: bool) -> Container:
    binds = {"/opt/simiam": base / "opt-simiam", "/opt/simiam-venv": base / "venv",
             "/usr/local/bin": base / "local-bin"}
    if job is not None:
        binds["/grade"] = job
    return Container(binds, namespaces)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("upload", UPLOADS)
def test_prairielearn(pl_image, secrets, tmp_path, kind, upload):
    job = tmp_path / "grade"
    (job / "student").mkdir(parents=True)
    _upload(upload, "prairielearn", tmp_path)(job / "student")
    shutil.copytree(pl_image / "package" / "serverFilesCourse", job / "serverFilesCourse")
    for path in [job / "serverFilesCourse", *(job / "serverFilesCourse").rglob("*")]:
        path.chmod(0o755 if path.is_dir() else 0o644)        # as a git checkout leaves them
    info = json.loads((pl_image / "package" / "question" / "info.json").read_text())
    entrypoint = info["externalGradingOptions"]["entrypoint"].split()
    done = _pl_container(pl_image, job, KINDS[kind]).run(entrypoint)
    assert done.returncode == 0, done.stdout + done.stderr
    text = (job / "results" / "results.json").read_text()
    assert prairielearn_violations(text) == []
    assert _leaks(text, secrets) == [] and str(SEED) not in done.stdout   # students see all of it
    results = json.loads(text)
    assert results["gradable"], text
    isolation = "bwrap: " if KINDS[kind] else f"subprocess: {OFFICIAL_PARTIAL}: "
    assert f"isolation: {isolation}" in results["message"] and "local check only" not in results["message"]
    passed = {t["name"]: t["points"] == t["max_points"] for t in results["tests"]}
    _expect(upload, results["score"] * 12.5, passed, text)
