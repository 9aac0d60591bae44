"""grade similarity: planted copies rank above every pair of independent solutions, the handout alone
scores ~0, and each kept wrong comparer (tests/data/similarity/wrong_comparers.py) is caught."""

from __future__ import annotations

import importlib.util
import io
import json
import re
import shutil
import zipfile
from pathlib import Path

import pytest
from similarity_class import DATA, PLANTED, STUBS, ranking_problems

from grader.cli import main as grade_main
from grader.similarity import command
from grader.similarity.command import THRESHOLD, read_class, run
from grader.similarity.compare import compare
from grader.similarity.submitted import MAX_BLOCK_CHARS, handout_blocks, student_code
from grader.similarity.tokens import block_tokens


def _scores(folder: Path) -> dict[frozenset, float]:
    codes = read_class(folder, 3).codes
    return {frozenset((p.a.id, p.b.id)): p.score for p in compare(codes, command.handout_blocks(3))}


def _wrong() -> dict:
    spec = importlib.util.spec_from_file_location("wrong_comparers", DATA.parent / "wrong_comparers.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.WRONG


def test_planted_copies_rank_above_independent_solutions(week3_class: Path) -> None:
    scores = _scores(week3_class)
    assert ranking_problems(scores, THRESHOLD) == [], sorted(scores.items(), key=lambda kv: -kv[1])


@pytest.mark.parametrize("name", sorted(_wrong()))
def test_wrong_comparer_is_caught(week3_class: Path, monkeypatch: pytest.MonkeyPatch, name: str) -> None:
    for module, attribute, replacement in _wrong()[name]:
        monkeypatch.setattr(importlib.import_module(module), attribute, replacement)
    scores = _scores(week3_class)
    assert ranking_problems(scores, THRESHOLD), f"{name}: not caught; scores {scores}"


def test_handout_alone_shares_nothing(week3_class: Path) -> None:
    codes = read_class(week3_class, 3).codes
    stubs = [c for c in codes if c.id in STUBS]
    assert [len(c.blocks) for c in stubs] == [8, 8], "the stub's 8 blocks are read, then blanked"
    pairs = compare(codes, handout_blocks(3))
    assert not [(p.a.id, p.b.id, p.score) for p in pairs if {p.a.id, p.b.id} & set(STUBS)]


def test_page_json_and_printed_list(week3_class: Path, tmp_path: Path) -> None:
    out = io.StringIO()
    report = run(3, week3_class, tmp_path / "out", stream=out)
    flagged = {frozenset((p["a"], p["b"])) for p in report["pairs"]}
    assert flagged == {frozenset(kv) for kv in PLANTED.items()}, report["pairs"]
    assert json.loads((tmp_path / "out" / "similarity.json").read_text()) == report
    first = report["pairs"][0]
    assert (first["a"], first["b"], first["score"]) == ("ana", "ana_renamed", 1.0)
    assert first["shared"] == first["fingerprints"][0] == first["fingerprints"][1] > 30, first
    # each of ana's week-3 blocks matches its own block in the renamed copy
    same = {m["a"] for m in first["blocks"] if m["a"] == m["b"]}
    assert same == {"go_to_goal.py: GoToGoal.__init__", "go_to_goal.py: GoToGoal.execute",
                    "go_to_goal.py: GoToGoal.execute (block 2)", "go_to_goal.py: GoToGoal.execute (block 3)",
                    "qb_supervisor.py: QBSupervisor.ensure_w"}, first["blocks"]
    printed = out.getvalue()
    assert printed.startswith("reading class folder (one folder or .zip per student id): class, 9 students\n"
                              "3 pairs score 60% or more\n    1. 100%  ana  ana_renamed  ("), printed
    page = (tmp_path / "out" / "similarity.html").read_text()
    assert page.count('<section class="pair"') == 3 and "Content-Security-Policy" in page
    # chen's ensure_w, copied by dana, is marked on both sides
    dana = page.split('id="pair-3"')[1]
    whole = re.findall(r"<mark>= robot.max_vel\nif vel_rl_max &gt; top:[^<]*vel_r_d, vel_l_d</mark>", dana)
    assert len(whole) == 2, dana


def test_one_block_copy_is_marked_in_that_block(week3_class: Path) -> None:
    codes = read_class(week3_class, 3).codes
    pair = next(p for p in compare(codes, handout_blocks(3)) if {p.a.id, p.b.id} == {"chen", "dana"})
    assert pair.blocks[0]["a"] == pair.blocks[0]["b"] == "qb_supervisor.py: QBSupervisor.ensure_w"
    dana = pair.b if pair.b.id == "dana" else pair.a
    spans = pair.spans[1] if pair.b.id == "dana" else pair.spans[0]
    ensure = next(i for i, b in enumerate(dana.blocks) if b.scope == "QBSupervisor.ensure_w")
    marked = sum(e - s for s, e in spans[ensure]) / len(dana.blocks[ensure].text.strip())
    assert marked > 0.9, f"only {marked:.0%} of the copied block is marked"


def test_hostile_ids_zips_and_blocks(tmp_path: Path) -> None:
    folder = tmp_path / "class"
    folder.mkdir()
    sol = Path(__file__).resolve().parents[2] / "solutions" / "week3"
    evil = "<img src=x onerror=alert(1)>" + "x" * 100
    for sid in (evil, "copy"):
        shutil.copytree(sol, folder / sid, ignore=shutil.ignore_patterns("__pycache__"))
    huge = ("        # START CODE BLOCK\n        zz = 'a' * 3  # " + "y" * 5_000_000
            + "\n        # END CODE BLOCK\n")
    gtg = (sol / "go_to_goal.py").read_text()
    (folder / "copy" / "go_to_goal.py").write_text(gtg.replace("# START CODE BLOCK", "# START CODE BLOCK\n"
                                                               "        '''", 1))
    (folder / evil / "quickbot.py").write_text((sol / "quickbot.py").read_text()
                                               + "\nclass Z:\n    def f(self):\n" + huge)
    (folder / "bidi\u202e").mkdir()
    (folder / "unbalanced").mkdir()
    (folder / "unbalanced" / "go_to_goal.py").write_text("# START CODE BLOCK\nx = 1\n")
    with zipfile.ZipFile(folder / "slip.zip", "w") as z:
        z.writestr("../go_to_goal.py", "x = 1\n")
    report = run(3, folder, tmp_path / "out", threshold=0.0, stream=None)
    assert list(report["not_compared"]) == ["bidi\u202e", "slip"], report["not_compared"]
    assert "outside" in report["not_compared"]["slip"]
    assert report["notes"][evil] == [f"quickbot.py: Z.f was cut to {MAX_BLOCK_CHARS} characters"]
    # its other blocks are still compared: the solution's week-3 blocks, as "copy" has them (the
    # broken first block of copy's go_to_goal.py aside)
    assert [(p["a"], p["b"]) for p in report["pairs"]] == [(evil, "copy")], report["pairs"]
    assert report["pairs"][0]["score"] > THRESHOLD, report["pairs"]
    assert "could not be told apart" in report["notes"]["unbalanced"][0]
    page = (tmp_path / "out" / "similarity.html").read_text()
    assert "<img" not in page and "&lt;img src=x onerror=alert(1)&gt;" + "x" * 35 + "…" in page
    assert "bidi\\u202e" in page
    assert "<li>unbalanced: go_to_goal.py: START CODE BLOCK has no END CODE BLOCK after it" in page
    assert len(page) < 1_000_000, len(page)


def test_tokens_normalise_names_and_survive_broken_text() -> None:
    words = [t.text for t in block_tokens("vel_r = 2.0 * v  # c\ns = '''open\n")]
    assert words[:6] == ["V", "=", "2", "*", "V", ";"], words
    assert words[6:] == ["V", "=", "S"] or words[6:8] == ["V", "="], words
    # numbers beyond a float once stopped the comparison (OverflowError): now a token as written
    assert [t.text for t in block_tokens("x = " + "9" * 400 + " + 1e999\n")] == ["V", "=", "9" * 32, "+",
                                                                                "1e999", ";"]


def test_block_reader_takes_only_blocks() -> None:
    text = "import os\n# START CODE BLOCK\nx = secret_handout_name + 1\n# END CODE BLOCK\nprint(os)\n"
    code = student_code("s", {"go_to_goal.py": text.encode()}, 3)
    assert [b.text for b in code.blocks] == ["x = secret_handout_name + 1\n"]


def test_cli(week3_class: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert grade_main(["similarity", "week3", str(week3_class), "--out", str(tmp_path / "o")]) == 0
    assert "3 pairs score 60% or more" in capsys.readouterr().out
    assert grade_main(["similarity", "week3", str(tmp_path / "nowhere")]) == 2
    assert "is not a folder of submissions" in capsys.readouterr().err
    assert grade_main(["similarity", "week3", str(week3_class), "--threshold", "7"]) == 2


def test_out_inside_the_class_folder_is_no_student(week3_class: Path, tmp_path: Path) -> None:
    folder = tmp_path / "class"
    shutil.copytree(week3_class, folder)
    for _ in range(2):   # the second run finds the first run's folder in the class folder
        report = run(3, folder, folder / "similarity")
    assert report["compared"] == 9 and report["not_compared"] == {}, report
