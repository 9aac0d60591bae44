"""`simiam migrate`: block by block, all or nothing, messages with file and line, exit codes 0/1/2."""

import importlib.util
import os
import shutil
from pathlib import Path

import pytest

from simiam.cli import main as cli
from simiam.course import migrate as migrate_module
from simiam.course.blocks import dedent_body, find_blocks, indent_body, replace_bodies

ROOT = Path(__file__).parents[2]
DATA = Path(__file__).parents[1] / "data" / "blocks"
MINE = (
    "_mine = 'my own version'\n"  # makes a body the student's own (its fingerprint differs from the course's)
)


def fill(folder: Path, week: int, extra: str = MINE) -> None:
    """Fill this week's new blocks the way a student would: the solution's code plus a line of their own."""
    from simiam.course.weeks import placeholder_for

    for path in sorted(folder.glob("*.py")):
        sol = (ROOT / "solutions" / f"week{week}" / path.name).read_text()
        sol_blocks = {b.key: b for b in find_blocks(sol, path.name)}
        text = path.read_text()
        blocks = find_blocks(text, path.name)
        bodies = {
            b.ordinal: indent_body(extra + dedent_body(sol_blocks[b.key].body), b.indent)
            for b in blocks
            if placeholder_for(path.name, b.scope, b.occurrence, week).week == week
        }
        path.write_text(replace_bodies(text, blocks, bodies))


def snapshot(folder: Path) -> dict:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def body_of(path: Path, scope: str, occurrence: int = 1) -> str:
    return next(b.body for b in find_blocks(path.read_text(), path.name) if b.key == (scope, occurrence))


@pytest.fixture
def w2w3(tmp_path, monkeypatch):
    """A student's filled week-2 folder and a fresh week-3 folder, side by side in the working directory."""
    monkeypatch.chdir(tmp_path)
    shutil.copytree(ROOT / "assignments/week2", tmp_path / "w2")
    shutil.copytree(ROOT / "assignments/week3", tmp_path / "w3")
    fill(tmp_path / "w2", 2)
    return tmp_path / "w2", tmp_path / "w3"


def run(*argv) -> int:
    return cli(["migrate", *map(str, argv)])


# ------------------------------------------------------------------------------------------- it moves


def test_week2_into_week3(w2w3, capsys):
    w2, w3 = w2w3
    before = snapshot(w3)
    assert run("week3", "--from", "w2", "--to", "w3") == 0
    out = capsys.readouterr().out
    assert (
        "  moved  w3/differential_drive.py:17  uni_to_diff: your code from w2/differential_drive.py:17" in out
    )
    assert "  moved  w3/qb_supervisor.py:" in out and "QBSupervisor.update_odometry: your code from" in out
    assert "  kept   w3/quickbot.py:19  get_ir_distances: shipped version kept: the IR sensors" in out
    assert (
        f"  kept   w3/go_to_goal.py:{_line(w3 / 'go_to_goal.py', 'GoToGoal.execute')}  GoToGoal.execute: new"
        in out
    )
    assert "Wrote differential_drive.py, qb_supervisor.py." in out
    # each body landed in its own function: the odometry did not go into ensure_w (the first block)
    assert MINE.strip() in body_of(w3 / "qb_supervisor.py", "QBSupervisor.update_odometry")
    assert body_of(w3 / "qb_supervisor.py", "QBSupervisor.ensure_w") == body_of(
        ROOT / "assignments/week3/qb_supervisor.py", "QBSupervisor.ensure_w"
    )
    assert body_of(w3 / "differential_drive.py", "uni_to_diff") == body_of(
        w2 / "differential_drive.py", "uni_to_diff"
    )
    after = snapshot(w3)
    assert [n for n in before if before[n] != after[n]] == ["differential_drive.py", "qb_supervisor.py"]
    for p in w3.glob("*.py"):
        compile(p.read_text(), p.name, "exec")
    # a second run changes nothing
    assert run("week3", "--from", "w2", "--to", "w3") == 0
    assert "already your code (migrated before)" in capsys.readouterr().out
    assert snapshot(w3) == after


def test_dry_run_changes_nothing(w2w3, capsys):
    w2, w3 = w2w3
    before = snapshot(w3)
    assert run("week3", "--from", w2, "--to", w3, "--dry-run") == 0
    assert (
        "Dry run: would write differential_drive.py, qb_supervisor.py; nothing was changed."
        in capsys.readouterr().out
    )
    assert snapshot(w3) == before


def test_default_target_is_assignments_weekN(w2w3, capsys):
    w2, w3 = w2w3
    (w3.parent / "assignments").mkdir()
    shutil.move(w3, w3.parent / "assignments" / "week3")
    assert run("week3", "--from", "w2") == 0
    assert MINE.strip() in body_of(w3.parent / "assignments/week3/differential_drive.py", "uni_to_diff")


def test_unfilled_blocks_are_kept_as_shipped(tmp_path, capsys):
    shutil.copytree(ROOT / "assignments/week2", tmp_path / "w2")
    shutil.copytree(ROOT / "assignments/week3", tmp_path / "w3")
    before = snapshot(tmp_path / "w3")
    assert run("week3", "--from", tmp_path / "w2", "--to", tmp_path / "w3") == 0
    out = capsys.readouterr().out
    assert "you had not filled it in week 2 (still the placeholder); shipped version kept: uni_to_diff" in out
    assert "Nothing to carry" in out
    assert snapshot(tmp_path / "w3") == before


def test_week3_into_week4(tmp_path, capsys):
    shutil.copytree(ROOT / "assignments/week3", tmp_path / "w3")
    shutil.copytree(ROOT / "assignments/week4", tmp_path / "w4")
    fill(tmp_path / "w3", 3)
    assert run("week4", "--from", tmp_path / "w3", "--to", tmp_path / "w4") == 0
    out = capsys.readouterr().out
    assert out.count("  moved  ") == 4  # GoToGoal: the gains and the three blocks of execute
    assert "qb_supervisor.py QBSupervisor.ensure_w: not carried, week 4 has no code block there" in out
    assert "update_odometry: same as the course shipped in week 3; this week's version kept" in out
    assert "Wrote go_to_goal.py." in out
    text = (tmp_path / "w4/go_to_goal.py").read_text()
    assert text.count(MINE.strip()) == 4


def test_reindented_source_is_reindented(w2w3, capsys):
    w2, w3 = w2w3
    src = w2 / "differential_drive.py"
    lines = src.read_text().splitlines(keepends=True)
    src.write_text("".join(line[(len(line) - len(line.lstrip(" "))) // 2 :] for line in lines))
    assert run("week3", "--from", w2, "--to", w3) == 0
    body = body_of(w3 / "differential_drive.py", "uni_to_diff")
    assert all(line.startswith("    ") for line in body.splitlines() if line.strip())
    compile((w3 / "differential_drive.py").read_text(), "differential_drive.py", "exec")


# ---------------------------------------------------------------------------------------- it refuses


def _line(path: Path, scope: str) -> int:
    return next(b.start_line for b in find_blocks(path.read_text(), path.name) if b.scope == scope)


def delete_file(w2, w3):
    (w2 / "qb_supervisor.py").unlink()
    return [f"{w2}/qb_supervisor.py: missing file"]


def delete_end(w2, w3):
    p = w2 / "qb_supervisor.py"
    line = _line(p, "QBSupervisor.update_odometry")
    p.write_text(p.read_text().replace("        # END CODE BLOCK\n", ""))
    return [f"{p}:{line}: START CODE BLOCK has no END CODE BLOCK"]


def duplicate_block(w2, w3):
    p = w2 / "differential_drive.py"
    text = p.read_text()
    [b] = find_blocks(text, p.name)
    lines = text.splitlines(keepends=True)
    block = lines[b.start_line - 1 : b.end_line]
    p.write_text("".join(lines[: b.end_line] + block + lines[b.end_line :]))
    return [
        f"{p}:{b.end_line + 1}: uni_to_diff has 2 code blocks, week 2 shipped 1 (START/END lines duplicated?)"
    ]


def delete_markers(w2, w3):
    p = w2 / "differential_drive.py"
    text = p.read_text()
    p.write_text(text.replace("    # START CODE BLOCK\n", "").replace("    # END CODE BLOCK\n", ""))
    return [f"{p}:12: uni_to_diff should have 1 code block(s) as week 2 shipped it, found 0"]


def syntax_error(w2, w3):
    p = w2 / "differential_drive.py"
    line = _line(p, "uni_to_diff")
    p.write_text(p.read_text().replace(MINE, "_mine = [\n", 1))
    return [f"{p}:{line + 1}: syntax error in the code block of uni_to_diff: '[' was never closed"]


def rename_function(w2, w3):
    p = w2 / "qb_supervisor.py"
    p.write_text(p.read_text().replace("def update_odometry(self):", "def update_odom(self):"))
    return [
        f"{p}: QBSupervisor.update_odometry should have 1 code block(s)",
        "a code block in QBSupervisor.update_odom, where week 2 has none",
    ]


def target_already_edited(w2, w3):
    p = w3 / "differential_drive.py"
    p.write_text(p.read_text().replace("vel_r = (2 * v + w * L) / (2 * R)", "vel_r = 2 * v / R"))
    return [
        f"{p}:17: you already changed the block of uni_to_diff in this week's folder; migrate will not "
        "overwrite it"
    ]


def target_markers_broken(w2, w3):
    p = w3 / "go_to_goal.py"
    second = _line(p, "GoToGoal.execute")
    p.write_text(p.read_text().replace("        # END CODE BLOCK\n", "", 1))
    return [f"{p}:{second - 1}: START CODE BLOCK inside the block opened at line 24"]


REFUSALS = [
    delete_file,
    delete_end,
    duplicate_block,
    delete_markers,
    syntax_error,
    rename_function,
    target_already_edited,
    target_markers_broken,
]


@pytest.mark.parametrize("breakage", REFUSALS, ids=lambda f: f.__name__)
def test_refuses_and_changes_nothing(w2w3, capsys, breakage):
    w2, w3 = w2w3
    expected = breakage(w2, w3)
    before = snapshot(w3)
    assert run("week3", "--from", w2, "--to", w3) == 1
    out = capsys.readouterr().out
    assert "Refused: nothing was changed." in out
    for text in expected:
        assert text in out, out
    assert snapshot(w3) == before  # the good blocks (e.g. uni_to_diff) were not written either


# ------------------------------------------------------------------------------------------ arguments


@pytest.mark.parametrize(
    "argv",
    [
        ["week1", "--from", "w2", "--to", "w3"],
        ["week9", "--from", "w2", "--to", "w3"],
        ["weekly", "--from", "w2", "--to", "w3"],
        ["week3", "--from", "nowhere", "--to", "w3"],
        ["week3", "--from", "w2", "--to", "nowhere"],
        ["week3", "--from", "w3", "--to", "w3"],
    ],
)
def test_bad_arguments_exit_2(w2w3, capsys, argv):
    before = snapshot(w2w3[1])
    assert run(*argv) == 2
    assert capsys.readouterr().err.startswith("simiam migrate: ")
    assert snapshot(w2w3[1]) == before


# ------------------------------------------------------------------------------------- atomic writing


def _wrong(name):
    spec = importlib.util.spec_from_file_location("wrong_migrate", DATA / "wrong_migrate.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return getattr(module, name)


def check_failed_write_changes_nothing(w2, w3, monkeypatch) -> None:
    """The disk fills up while the second file is being written: no file changes, no temporary file left."""
    real_fsync, calls = os.fsync, []

    def failing_fsync(fd):
        calls.append(fd)
        if len(calls) == 2:
            raise OSError(28, "No space left on device")
        real_fsync(fd)

    before = snapshot(w3)
    monkeypatch.setattr(os, "fsync", failing_fsync)
    assert run("week3", "--from", w2, "--to", w3) == 1
    monkeypatch.setattr(os, "fsync", real_fsync)
    assert snapshot(w3) == before


def test_failed_write_changes_nothing(w2w3, monkeypatch, capsys):
    check_failed_write_changes_nothing(*w2w3, monkeypatch)
    assert "No space left on device" in capsys.readouterr().err


def test_wrong_writer_is_caught(w2w3, monkeypatch):
    monkeypatch.setattr(migrate_module, "write_atomically", _wrong("write_in_place"))
    with pytest.raises((AssertionError, OSError)):
        check_failed_write_changes_nothing(*w2w3, monkeypatch)


def test_wrong_body_check_is_caught(w2w3, monkeypatch, capsys):
    monkeypatch.setattr(migrate_module, "check_body", _wrong("check_body_verbatim"))
    with pytest.raises(AssertionError):
        test_reindented_source_is_reindented(w2w3, capsys)


def test_week1_into_week2_has_nothing_to_carry(tmp_path, capsys):
    shutil.copytree(ROOT / "assignments/week1", tmp_path / "w1")
    shutil.copytree(ROOT / "assignments/week2", tmp_path / "w2")
    before = snapshot(tmp_path / "w2")
    assert run("week2", "--from", tmp_path / "w1", "--to", tmp_path / "w2") == 0
    out = capsys.readouterr().out
    [line] = [ln for ln in out.splitlines() if "new this week: yours to write" in ln]  # one line, 3 blocks
    assert line.count(", ") == 2
    assert "Nothing to carry" in out
    assert snapshot(tmp_path / "w2") == before


def test_nothing_to_carry_is_said_in_a_few_short_lines(tmp_path, capsys, monkeypatch):
    """With nothing to carry, migrate printed a line per block (13 for week 4), each with the absolute
    path of the resolved week folder: now one line per reason, paths as typed from the current folder."""
    for week in (3, 4):
        shutil.copytree(ROOT / f"assignments/week{week}", tmp_path / f"week{week}")
    monkeypatch.chdir(tmp_path)
    assert run("week4", "--from", "week3") == 0
    out = capsys.readouterr().out
    lines = out.strip().splitlines()
    assert lines[0] == "simiam migrate week4: from week3 into week4"
    assert lines[-1].startswith("Nothing to carry")
    assert len(lines) <= 6 and str(tmp_path) not in out
