"""Every command in README.md, docs/*.md and the handout READMEs runs as written (tests/docs/documented.py
extracts them): the handouts' in a student's course folder, the others in a copy of the checkout; and the
few not run are listed with a reason. Also: no command hides in an unlabelled block, every relative link of
the docs leads to a file of the repository, and the suite's figures are quoted in one place only.

The folders are prepared once for the module (handouts of all seven weeks, a checkout copy with two
submissions for the batch commands)."""

from __future__ import annotations

import re
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest
from documented import ROOT, SKIPPED, Command, clean_env, doc_files, documented, run, runnable, skip_of

COMMANDS, HIDDEN = documented()
BLOCKS: dict[tuple[str, int], list[Command]] = {}
for _c in COMMANDS:
    BLOCKS.setdefault((_c.file, _c.block), []).append(_c)
WRONG = ROOT / "tests" / "data" / "docs_wrong"
# `grade weekN` of a handout as shipped (or a checkout's stub) does not pass every check: exit status 1
GRADES_A_WEEK = re.compile(r"^grade week\d(?!.*--solutions)")
IGNORED = shutil.ignore_patterns(".git", ".venv", "build", "dist", "runs", "reports", "__pycache__",
                                 "*.egg-info", ".ruff_cache", ".pytest_cache", ".mypy_cache")


def _checkout_copy(home: Path, name: str) -> Path:
    """A copy of the checkout under `home`, with submissions/alice (the week-3 solution) and
    submissions/bob.zip (the week-3 stub) for the batch commands."""
    checkout = home / name
    shutil.copytree(ROOT, checkout, ignore=IGNORED)
    submissions = checkout / "submissions"
    shutil.copytree(ROOT / "solutions" / "week3", submissions / "alice")
    with zipfile.ZipFile(submissions / "bob.zip", "w") as z:
        for f in sorted((ROOT / "assignments" / "week3").glob("*.py")):
            z.write(f, f"week3/{f.name}")
    return checkout


@pytest.fixture(scope="module")
def folders(tmp_path_factory) -> dict[str, Path]:
    """{"home", "student", "marker", and one checkout copy per documented file}: a temporary home holding
    the student's course folder ~/course with the handout of every week (the handout READMEs' commands
    run there, week after week, as a student goes), and a fresh copy of the checkout for each other
    page (each page is read on its own: the README's `--out release/` is no reason for platforms.md's to
    find the folder taken)."""
    home = tmp_path_factory.mktemp("home")
    student = home / "course"
    env = clean_env(home)
    for week in range(1, 8):
        subprocess.run(["grade", "handout", f"week{week}", "--out", str(home / "release")], env=env,
                       check=True, capture_output=True)
        shutil.move(home / "release" / f"week{week}", student / f"week{week}")
    out = {"home": home, "student": student, "marker": home / ".where"}
    for file in sorted({c.file for c in COMMANDS
                        if c.folder == "checkout" and skip_of(c, BLOCKS[(c.file, c.block)]) is None}):
        out[file] = _checkout_copy(home, "checkout-" + re.sub(r"\W", "-", file))
    return out


def _problem(text: str, ran) -> str | None:
    """What is wrong with a documented command's run, or None."""
    allowed = (0, 1) if GRADES_A_WEEK.match(text) else (0,)
    if ran.returncode not in allowed:
        return f"exit status {ran.returncode}"
    if "Traceback (most recent call last)" in ran.output:
        return "a traceback"
    if ran.returncode == 1 and "total:" not in ran.output:
        return "exit status 1 without a total"
    return None


def run_block(block: list[Command], folders: dict[str, Path]) -> tuple[list[str], int]:
    """Run a block's commands in order (a `cd` carries over); (the problems, how many ran)."""
    first = block[0]
    cwd = folders["student"] if first.folder == "student" else folders.get(first.file, folders["home"])
    env, problems, ran_count = clean_env(folders["home"]), [], 0
    for command in block:
        if skip_of(command, block) is not None:
            continue
        text = runnable(command)
        ran = run(text, cwd, env, folders["marker"])
        ran_count += 1
        problem = _problem(text, ran)
        if problem:
            problems.append(f"{command.where()}\n  {problem}:\n{ran.output[-1500:]}")
        cwd = ran.cwd
    return problems, ran_count


@pytest.mark.parametrize("key", list(BLOCKS), ids=[f"{f}#{b}" for f, b in BLOCKS])
def test_the_documented_commands_run_as_written(key: tuple[str, int], folders: dict[str, Path]) -> None:
    block = BLOCKS[key]
    problems, _ = run_block(block, folders)
    assert problems == []


def test_the_skip_list_is_short_and_every_entry_still_skips_something() -> None:
    """A skip that matches nothing hides no command but says one is tested elsewhere: it must go; and
    more than a handful would mean the docs test no longer tests the docs."""
    assert len(SKIPPED) <= 7
    for skip in SKIPPED:
        assert any(skip.matches(c.text) for c in COMMANDS), f"no documented command matches {skip.pattern!r}"
    ran = [c for c in COMMANDS if skip_of(c, BLOCKS[(c.file, c.block)]) is None]
    assert len(ran) >= 30, (len(ran), len(COMMANDS))
    for expected in ("grade week3 --batch submissions/ --out graded/", "simiam migrate week5 --from week4",
                     "grade package prairielearn week3", "simiam run week3 --dt 0.05 --seconds 10"):
        assert any(c.text.startswith(expected) for c in ran), expected


def test_no_command_hides_in_an_unlabelled_block() -> None:
    """A command in a ``` block without `bash` would never be run by this test."""
    assert HIDDEN == []


def test_wrong_docs_fail(folders: dict[str, Path]) -> None:
    """The same runner on commands a doc must not give: a misspelt option, a checkout path in a handout
    README (a student has no assignments/), a subcommand that does not exist. Each one fails."""
    from documented import commands_in

    text = (WRONG / "README.md").read_text(encoding="utf-8")
    wrong, _ = commands_in(text, "assignments/week5/README.md")
    assert len(wrong) == 4
    for command in wrong:
        problems, ran = run_block([command], folders)
        assert ran == 1 and len(problems) == 1, command.text


def test_relative_links_lead_to_files_of_the_repository() -> None:
    """A clone has only what is in it: "../shared/" and the like are no link a reader can follow."""
    broken = []
    for path in doc_files():
        for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", path.read_text(encoding="utf-8")):
            if "://" in target or target.startswith("mailto:"):
                continue
            resolved = (path.parent / target).resolve()
            if not resolved.exists() or ROOT.resolve() not in resolved.parents:
                broken.append(f"{path.relative_to(ROOT)}: {target}")
    assert broken == []


def test_the_suite_figures_are_quoted_in_one_place() -> None:
    """The README, contributing.md and the measured suite disagreed on the suite's length and size: its
    figures (N tests, N s) are quoted in the README's table only; other pages point there."""
    figure = re.compile(r"\b\d[\d,]{2,} tests\b")
    quoted = {p.relative_to(ROOT).as_posix(): len(figure.findall(p.read_text(encoding="utf-8")))
              for p in doc_files()}
    assert {p: n for p, n in quoted.items() if n} == {"README.md": 1}
    assert "the README's table" in (ROOT / "docs" / "contributing.md").read_text(encoding="utf-8")


def _options(parser, command: str) -> list[tuple[str, str]]:
    """(command, --option) of `parser` and of its subcommands'."""
    out = []
    for action in parser._actions:
        if isinstance(getattr(action, "choices", None), dict):
            for name, sub in action.choices.items():
                out += _options(sub, f"{command} {name}")
        out += [(command, o) for o in action.option_strings if o.startswith("--") and o != "--help"]
    return out


def test_every_option_of_run_migrate_and_grade_is_documented() -> None:
    """`simiam run --world` was documented only in --help: every option of `simiam run`, `simiam migrate`
    and `grade` appears in a paragraph or block of the docs that names its command."""
    from grader.cli import _parser as grade_parser
    from simiam.cli import _parser as simiam_parser

    paragraphs = [p for path in doc_files() for p in re.split(r"\n\s*\n", path.read_text(encoding="utf-8"))]
    wanted = [(c, o) for c, o in _options(simiam_parser(), "simiam") + _options(grade_parser(), "grade")
              if c in ("simiam run", "simiam migrate", "grade")]
    assert ("simiam run", "--world") in wanted and len(wanted) > 20
    missing = [(c, o) for c, o in wanted
               if not any(c in p and re.search(re.escape(o) + r"\b", p) for p in paragraphs)]
    assert missing == []


def test_the_readme_instructor_line_grades_with_the_hidden_checks(folders: dict[str, Path]) -> None:
    """Issue 29: the README's `grade week3 --batch submissions/ --out graded/` gave official-looking
    grades without the hidden checks. Run as written (in the README's checkout copy: a rerun after the
    block test only resumes), every result ran week 3's hidden checks with the folder's secret seed."""
    import json

    line = next(c for c in COMMANDS if c.file == "README.md" and c.text.startswith("grade week3 --batch "))
    checkout = folders["README.md"]
    ran = run(runnable(line), checkout, clean_env(folders["home"]), folders["marker"])
    assert ran.returncode in (0, 1), ran.output[-1500:]
    out = checkout / line.text.split("--out ")[1].split()[0]
    seed = json.loads((out / ".seed").read_text())["seed"]
    for student in ("alice", "bob"):
        result = json.loads((out / f"{student}.json").read_text())
        hidden = [c["id"] for c in result["checks"] if c.get("visibility") == "hidden"]
        assert (result["hidden"], result["hidden_checks_not_run"], result["seed"]) == (True, 0, seed), student
        assert sorted(hidden) == ["week3.go_to_goal.other_goals", "week3.pid.tracking_other_goal"], hidden
        assert result["batch"]["hidden_set"]["checks"] == sorted(hidden)
    record = json.loads((out / "batch.json").read_text())
    assert record["hidden"] is True and record["hidden_set"]["seed"] == seed
