"""Issue 11, done means: the wheel a student installs holds no answers, and works outside the checkout.

One wheel is built from this tree and installed into one fresh virtual environment outside the checkout
per test session (pip's cache keeps it cheap). A course folder elsewhere receives copies of
assignments/week3 and week4, and the installed console scripts run there: the stub scores 0, the solution
blocks pasted in score full marks, an edit outside the blocks is reported and not run, `simiam run` and
`simiam migrate` work with the default-folder rule, and the wheel's files hold no solution block's code.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import venv
import zipfile
from pathlib import Path

import pytest
from answer_search import answers_of, search

from grader.sandbox.isolation import bwrap_works
from simiam.course.blocks import find_blocks
from simiam.course.splice import splice

REPO = Path(__file__).resolve().parents[2]
pytestmark = pytest.mark.slow

# What a wheel build needs from the tree (tests, solutions, instructor_tools and the rest stay behind).
SOURCES = ("pyproject.toml", "README.md", "simiam", "grader")
_JUNK = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info")

def _run(argv: list, cwd: Path, env: dict, timeout: float = 600) -> subprocess.CompletedProcess:
    return subprocess.run([str(a) for a in argv], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=timeout)


def _isolation() -> list[str]:
    """--no-build-isolation when this environment can build already (setuptools >= 68 and wheel), so the
    build downloads nothing; otherwise pip fetches them into an isolated build environment (from its cache
    after the first time)."""
    try:
        import setuptools
        import wheel  # noqa: F401
    except ImportError:
        return []
    return ["--no-build-isolation"] if int(setuptools.__version__.split(".")[0]) >= 68 else []


@pytest.fixture(scope="session")
def wheel(tmp_path_factory) -> Path:
    """`pip wheel --no-deps` of a copy of this tree (the build writes build/ next to its sources)."""
    base = tmp_path_factory.mktemp("wheel")
    src = base / "src"
    for name in SOURCES:
        path = REPO / name
        if path.is_dir():
            shutil.copytree(path, src / name, ignore=_JUNK)
        else:
            src.mkdir(exist_ok=True)
            shutil.copy(path, src / name)
    done = _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", *_isolation(), "-w", base / "dist",
                 src], base, dict(os.environ))
    assert done.returncode == 0, done.stdout + done.stderr
    (found,) = (base / "dist").glob("simiam-*.whl")
    return found


@pytest.fixture(scope="session")
def student(wheel: Path, tmp_path_factory) -> dict:
    """A fresh venv with only the wheel (and its dependencies) installed; the env to run its scripts."""
    home = tmp_path_factory.mktemp("student")
    env_dir = home / "venv"
    venv.EnvBuilder(with_pip=True).create(env_dir)
    bin_dir = env_dir / "bin"
    env = {"PATH": f"{bin_dir}:{_system_path()}", "HOME": str(home), "LANG": "C.UTF-8"}
    # pip itself runs with this machine's settings (index, proxy, cache); the student's commands do not
    pip_env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME")}
    pip_env["PATH"] = env["PATH"]
    done = _run([bin_dir / "python", "-m", "pip", "install", "-q", wheel], home, pip_env)
    assert done.returncode == 0, done.stdout + done.stderr
    where = _run([bin_dir / "python", "-c", "import grader, simiam; print(grader.__file__, simiam.__file__)"],
                 home, env)
    assert str(env_dir) in where.stdout and str(REPO) not in where.stdout, where.stdout + where.stderr
    return {"env": env, "bin": bin_dir, "home": home}


def _system_path() -> str:
    """This run's PATH without any virtual environment's bin/: the machine's commands as this run finds them
    (where bwrap is hidden, .ci/run's second run, the student's `grade` must not find it either)."""
    folders = [d for d in os.environ.get("PATH", "").split(os.pathsep)
               if d and not (Path(d).parent / "pyvenv.cfg").exists()]
    return os.pathsep.join(folders) or "/usr/bin:/bin"


def _course(student: dict, name: str, weeks: tuple[int, ...] = (3,)) -> Path:
    """A student's course folder outside the checkout holding copies of assignments/weekN."""
    folder = student["home"] / name
    for week in weeks:
        shutil.copytree(REPO / "assignments" / f"week{week}", folder / f"week{week}")
    return folder


def _paste_solution_blocks(folder: Path, week: int) -> None:
    """Paste every code block of solutions/weekN into the student's copy (what a student who solved the
    week has); everything outside the blocks stays the student's file."""
    for path in sorted(folder.glob("*.py")):
        solution = (REPO / "solutions" / f"week{week}" / path.name).read_text()
        result = splice(path.read_text(), solution, path.name)
        assert not result.errors and not result.outside_edits
        path.write_text(result.text)


def _grade(student: dict, cwd: Path, *args: str) -> tuple[subprocess.CompletedProcess, dict]:
    report = cwd / "result.json"  # --json: also when --check leaves the report alone
    done = _run([student["bin"] / "grade", *args, "--out", "graded", "--json", report], cwd, student["env"])
    assert report.is_file(), done.stdout + done.stderr
    return done, json.loads(report.read_text())


def test_the_stub_scores_zero_on_the_coded_parts(student: dict) -> None:
    course = _course(student, "stub")
    done, result = _grade(student, course, "week3")  # the folder holding week3: ./week3
    assert done.returncode == 1, done.stdout + done.stderr
    assert result["status"] == "graded" and result["max_score"] > 0
    assert [c["points"] for c in result["checks"]] == [0] * len(result["checks"])
    said = " ".join(done.stdout.split())  # the terminal output wraps at its width
    assert "hidden check" in said and "run at official grading" in said
    assert result["hidden"] is False and result["hidden_checks_not_run"] > 0


def test_the_solution_blocks_pasted_in_score_full_marks(student: dict) -> None:
    course = _course(student, "solved")
    _paste_solution_blocks(course / "week3", 3)
    done, result = _grade(student, course / "week3", "week3")  # inside the week folder
    assert done.returncode == 0, done.stdout + done.stderr
    assert result["score"] == result["max_score"] > 0
    assert result["isolation"] == ("bwrap" if bwrap_works()[0] else "subprocess")


def test_an_edit_outside_the_blocks_is_reported_and_not_run(student: dict) -> None:
    course = _course(student, "outside")
    _paste_solution_blocks(course / "week3", 3)
    controller = course / "week3" / "go_to_goal.py"
    sabotage = "GoToGoal.execute = lambda *args, **kwargs: (0.0, 0.0)  # outside every block"
    controller.write_text(controller.read_text() + "\n" + sabotage + "\n")
    done, result = _grade(student, course, "week3")
    assert result["score"] == result["max_score"], done.stdout  # the edit did not run
    assert any("go_to_goal.py" in n and "GoToGoal.execute = lambda" in n for n in result["notices"])
    assert "changed outside the code blocks" in done.stdout


def test_run_and_migrate_work_in_a_course_folder(student: dict) -> None:
    course = _course(student, "migrate", weeks=(3, 4))
    _paste_solution_blocks(course / "week3", 3)
    mine = course / "week3" / "go_to_goal.py"
    mine.write_text(mine.read_text().replace("self.Kp = 2.5", "self.Kp = 3.25"))  # the student's own gain
    done = _run([student["bin"] / "simiam", "run", "week3", "--seconds", "2"], course / "week3",
                student["env"])
    assert done.returncode == 0, done.stdout + done.stderr
    assert list((course / "week3" / "runs").glob("*.html"))
    done = _run([student["bin"] / "simiam", "migrate", "week4", "--from", "week3"], course, student["env"])
    assert done.returncode == 0, done.stdout + done.stderr
    assert "moved" in done.stdout and "from week3 into week4\n" in done.stdout  # as typed in course/
    assert "self.Kp = 3.25" in (course / "week4" / "go_to_goal.py").read_text()


def test_practice_runs_from_the_installed_package(student: dict) -> None:
    """`grade week3 --practice` finds the practice set in the installed package (no checkout): the hidden
    tracking check runs on its practice goals, shown apart, and the stub fails them."""
    course = _course(student, "practice")
    done, result = _grade(student, course, "week3", "--practice", "--check", "week3.pid.tracking_other_goal")
    (check,) = result["practice"]["checks"]
    assert check["visibility"] == "practice" and check["status"] != "passed", done.stdout
    assert "goal (-0.175, -0.845)" in check["message"] and result["checks"] == []
    assert "practice (not graded)" in done.stdout and done.returncode == 1


def test_instructor_tools_are_not_there_and_say_so(student: dict) -> None:
    home = student["home"]
    done = _run([student["bin"] / "grade", "week3", "--solutions"], home, student["env"])
    assert done.returncode == 2 and "--solutions needs the course checkout" in done.stderr
    done = _run([student["bin"] / "simiam", "bench", "--seconds", "0.1"], home, student["env"])
    assert done.returncode == 2 and "instructor tooling in the course checkout" in done.stderr
    done = _run([student["bin"] / "grade", "week9"], home, student["env"])
    assert done.returncode == 2


# The installed package sits in site-packages, next to numpy: reach it by name or by file.
CHEAT = '''
    import importlib.util
    import os

    import numpy

    site = os.path.dirname(os.path.dirname(numpy.__file__))
    try:
        import grader.reference as ref
    except ImportError:
        ref = None
    path = os.path.join(site, 'grader', 'reference.py')
    if ref is None and os.path.exists(path):
        spec = importlib.util.spec_from_file_location('stolen', path)
        ref = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(ref)
    vel_r, vel_l = (1.0, 1.0) if ref else (0, 0)  # anything of the grader's would do
'''


@pytest.mark.sandbox
@pytest.mark.skipif(not bwrap_works()[0], reason="only bubblewrap hides files; subprocess mode says so")
def test_the_installed_reference_code_is_out_of_reach_of_student_code(student: dict) -> None:
    course = _course(student, "cheat", weeks=(2,))
    drive = course / "week2" / "differential_drive.py"
    text = drive.read_text()
    (block,) = [b for b in find_blocks(text, drive.name) if b.scope == "uni_to_diff"]
    lines = text.splitlines(keepends=True)
    drive.write_text("".join(lines[:block.start_line] + [CHEAT.lstrip("\n")] + lines[block.end_line - 1:]))
    done, result = _grade(student, course, "week2", "--check", "week2.uni_to_diff.round_trip")
    check = result["checks"][0]
    assert check["points"] == 0 and "your vel_r was 0" in check["message"], done.stdout


def test_the_wheel_holds_no_answers(wheel: Path) -> None:
    """No file of the wheel holds an answer of any block of solutions/ (lines, or the same maths in other
    wording: tests/packaging/answer_search.py), and no file of solutions/, instructor_tools/ or the tests."""
    answers = answers_of(REPO)
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        assert not [n for n in names if n.startswith(("solutions/", "assignments/", "instructor_tools/",
                                                      "tests/"))]
        assert not [n for n in names if "reference_brains" in n or "hidden/" in n and n.endswith(".json")]
        assert any(n.startswith("simiam/course/skeletons/week4/") for n in names)
        assert {"grader/reference.py", "grader/checks/expected/week2_odometry_course_test.json"} <= set(names)
        # the practice sets ship (grade weekN --practice); the hidden sets they were kept apart from do not
        assert {f"grader/practice/week{w}.json" for w in range(3, 8)} <= set(names)
        hidden = {p.read_bytes() for p in (REPO / "instructor_tools" / "hidden").glob("week*.json")}
        assert len(hidden) == 4 and not [n for n in names if z.read(n) in hidden]
        hits = search(((n, z.read(n).decode("utf-8", errors="replace")) for n in names), answers)
    assert hits == {}


def test_the_entry_points_are_plain_console_scripts(wheel: Path) -> None:
    """Issue 23: pip makes a console script an .exe launcher on Windows; a GUI script or any other kind of
    entry point would not print to the student's terminal. The built metadata holds exactly the console
    scripts pyproject.toml names, and each target takes an optional argv (the launcher calls it bare)."""
    import configparser
    import inspect
    from importlib import import_module

    tomllib = pytest.importorskip("tomllib")  # Python 3.11+

    with zipfile.ZipFile(wheel) as archive:
        (name,) = [n for n in archive.namelist() if n.endswith(".dist-info/entry_points.txt")]
        text = archive.read(name).decode()
    built = configparser.ConfigParser()
    built.read_string(text)
    declared = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
    assert built.sections() == ["console_scripts"]
    assert dict(built["console_scripts"]) == declared["scripts"] == {"simiam": "simiam.cli:main",
                                                                     "grade": "grader.cli:main"}
    assert "gui-scripts" not in declared and "entry-points" not in declared
    for target in declared["scripts"].values():
        module, _, function = target.partition(":")
        parameters = list(inspect.signature(getattr(import_module(module), function)).parameters.values())
        assert [(p.name, p.default) for p in parameters] == [("argv", None)]
