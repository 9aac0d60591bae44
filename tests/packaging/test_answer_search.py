"""Issue 11: no file that goes into the student's wheel holds an answer, and the search can find one.

What counts as an answer is derived from the blocks of solutions/ (tests/packaging/answer_search.py).
These tests run on the source tree (fast); test_wheel.py runs the same search over the built wheel.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from answer_search import Answers, answers_of, found_in, search

REPO = Path(__file__).resolve().parents[2]
WRONG = REPO / "tests" / "data" / "wheel_answers"
PACKAGED = ("simiam", "grader")  # what pyproject.toml packages (tests/packaging/test_wheel.py: the wheel)


@pytest.fixture(scope="module")
def answers() -> Answers:
    return answers_of(REPO)


def _packaged_files() -> list[tuple[str, str]]:
    files = []
    for top in PACKAGED:
        for path in sorted((REPO / top).rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts:
                files.append((str(path.relative_to(REPO)), path.read_text(errors="replace")))
    return files


def test_every_block_of_every_week_gives_answers(answers: Answers) -> None:
    """The search has something to find in every block that computes something (weeks 2-4 today, and any
    week whose solutions/ exist tomorrow)."""
    assert len(answers.lines) > 40 and len(answers.shapes) > 30
    for block in ("differential_drive.py uni_to_diff", "QBSupervisor.update_odometry",
                  "QBSupervisor.ensure_w", "quickbot.py get_ir_distances", "GoToGoal.execute",
                  "AvoidObstacles.get_transformation_matrix", "AvoidObstacles.apply_sensor_geometry",
                  "AvoidObstacles.execute"):
        assert any(block in where for where in answers.blocks()), block


def test_the_packaged_source_holds_no_answers(answers: Answers) -> None:
    """Every file under simiam/ and grader/ (the skeletons too: their blocks are placeholders)."""
    files = _packaged_files()
    assert any(name == "grader/reference.py" for name, _ in files)
    assert search(files, answers) == {}


@pytest.mark.parametrize(("wrong", "block"), [
    ("old_reference.py", "QBSupervisor.ensure_w"),              # the shift of both wheels, other names
    ("old_reference.py", "QBSupervisor.update_odometry"),       # d_c, cos and sin in one function
    ("old_reference.py", "AvoidObstacles.get_transformation_matrix"),  # c, s = cos, sin; [[c, -s, x], ..]
    ("old_reference.py", "GoToGoal.execute"),                   # atan2(y_g - y, x_g - x)
    ("old_dynamics.py", "differential_drive.py uni_to_diff"),
    ("old_bench.py", "differential_drive.py uni_to_diff"),
    ("old_bench.py", "QBSupervisor.update_odometry"),
    ("old_probes.py", "AvoidObstacles.get_transformation_matrix"),
    ("uni_to_diff_rearranged.py", "differential_drive.py uni_to_diff"),  # (v + w L/2)/R: by its values
])
def test_the_search_finds_answers_in_other_wording(answers: Answers, wrong: str, block: str) -> None:
    """The wrong versions (tests/data/wheel_answers/): the files as they were before this search existed."""
    hits = found_in((WRONG / wrong).read_text(), answers)
    assert any(block in hit for hit in hits), hits


def test_ordinary_geometry_alone_is_not_an_answer(answers: Answers) -> None:
    """The simulator must move along a heading and the report must take midpoints: one small expression
    shared with a block is not an answer; three of one block in one function are."""
    move = ("def move(x, y, theta, chord, heading):\n"
            "    return x + chord * math.cos(heading), y + chord * math.sin(heading)\n")
    assert found_in(move, answers) == []
    odometry = ("def step(x, y, theta, d_r, d_l):\n    d = (d_r + d_l) / 2\n"
                "    return x + d * math.cos(theta), y + d * math.sin(theta)\n")
    assert any("QBSupervisor.update_odometry" in hit for hit in found_in(odometry, answers))


def test_a_new_weeks_blocks_count_without_naming_them(tmp_path: Path) -> None:
    """A block of a week that does not exist yet becomes an answer as soon as its solution exists."""
    repo = tmp_path / "repo"
    shutil.copytree(REPO / "solutions", repo / "solutions")
    shutil.copytree(REPO / "assignments", repo / "assignments")
    (repo / "solutions" / "week9").mkdir()
    (repo / "solutions" / "week9" / "blend.py").write_text(
        "import math\n\n\ndef blend(u_gtg, u_ao, alpha):\n    # START CODE BLOCK\n"
        "    u = [alpha * u_gtg[0] + (1 - alpha) * u_ao[0], alpha * u_gtg[1] + (1 - alpha) * u_ao[1]]\n"
        "    # END CODE BLOCK\n    return u\n")
    new = answers_of(repo)
    assert any("week9/blend.py" in where for where in new.blocks())
    paraphrase = "def mix(a, b, k):\n    return [k * a[0] + (1 - k) * b[0], 0]\n"
    assert any("week9/blend.py" in hit for hit in found_in(paraphrase, new))
