"""The committed stubs are exactly what `python -m simiam.course.stubs` generates from the solutions, and
the placeholder table agrees with the solutions (no drift in either direction)."""

import ast
import importlib.util
import re
from pathlib import Path

import pytest

from simiam.course.blocks import BlockError, dedent_body, find_blocks, fingerprint
from simiam.course.placeholders import Placeholder
from simiam.course.splice import splice
from simiam.course.stubs import ROOT, differences, generate, main, stub_text, write
from simiam.course.weeks import all_blocks, placeholder_for, week_numbers

WEEKS = week_numbers()

DATA = Path(__file__).parents[1] / "data" / "blocks"


def solution_files(root: Path = ROOT):
    for week in WEEKS:
        for path in sorted((root / "solutions" / f"week{week}").glob("*.py")):
            yield week, path


# ----------------------------------------------------------------------------------------- drift checks


def check_stubs_match_solutions(root: Path) -> None:
    """Outside the blocks every stub is its solution, line for line (splicing the solution gives it back)."""
    for week, sol in solution_files():
        stub = root / "assignments" / f"week{week}" / sol.name
        assert stub.is_file(), f"{stub} missing"
        result = splice(stub.read_text(), sol.read_text(), sol.name)
        assert not result.errors, [str(e) for e in result.errors]
        assert not result.outside_edits, f"week{week}/{sol.name}: " + "\n".join(
            map(str, result.outside_edits)
        )
        assert result.text == sol.read_text()


def test_committed_stubs_are_what_the_generator_writes():
    assert differences(generate()) == []


def test_committed_stubs_match_solutions_outside_blocks():
    check_stubs_match_solutions(ROOT)


def test_drift_is_detected(tmp_path):
    """A stub edited by hand outside its blocks, and a stale extra stub, are both caught."""
    generated = generate()
    write(generated, tmp_path)
    assert differences(generated, tmp_path) == []
    stub = tmp_path / "assignments/week3/go_to_goal.py"
    stub.write_text(stub.read_text().replace("self.E_k = 0", "self.E_k = 1"))
    (tmp_path / "assignments/week2/old.py").write_text("x = 1\n")
    assert differences(generated, tmp_path) == [
        "assignments/week3/go_to_goal.py",
        "assignments/week2/old.py (no longer in solutions/)",
    ]
    with pytest.raises(AssertionError, match="changed outside the code blocks"):
        check_stubs_match_solutions(tmp_path)


def test_check_mode_exit_status(tmp_path, capsys):
    write(generate(), tmp_path)
    assert main(["--check", "--root", str(tmp_path)]) == 0
    (tmp_path / "assignments/week4/quickbot.py").write_text("# stale\n")
    assert main(["--check", "--root", str(tmp_path)]) == 1
    assert "out of date: assignments/week4/quickbot.py" in capsys.readouterr().out


# ------------------------------------------------------------------------------- what each week ships


@pytest.mark.parametrize("week", [w for w in WEEKS if w > 1])
def test_new_blocks_are_placeholders_and_earlier_ones_are_filled(week):
    new = 0
    for w, sol in solution_files():
        if w != week:
            continue
        stub = ROOT / "assignments" / f"week{week}" / sol.name
        for s, b in zip(
            find_blocks(sol.read_text(), sol.name), find_blocks(stub.read_text(), sol.name), strict=True
        ):
            spec = placeholder_for(sol.name, s.scope, s.occurrence, week)
            if spec.week == week:
                new += 1
                assert fingerprint(b.body) == fingerprint(spec.code), f"{sol.name} {s.describe()}"
                assert "#" in b.body  # the hint is there
            else:
                assert b.body == s.body, f"{sol.name} {s.describe()} should ship filled in week {week}"
    assert new > 0


def test_week1_has_no_blocks():
    assert all(find_blocks(p.read_text(), p.name) == [] for p in (ROOT / "assignments/week1").glob("*.py"))


# ------------------------------------------------------------------------------------ placeholder table


def test_every_table_entry_is_used_in_its_week():
    found = {
        (w, p.name, b.scope, b.occurrence)
        for w, p in solution_files()
        for b in find_blocks(p.read_text(), p.name)
    }
    for spec in all_blocks():
        assert (spec.week, *spec.key) in found, f"stale entry: {spec.key} (week {spec.week})"


def test_revised_blocks_are_the_ones_whose_shipped_code_changes():
    """A filled block whose code changes from week w-1 to week w must say why (revised or tunable)."""
    bodies = {
        (w, p.name, b.key): b.body for w, p in solution_files() for b in find_blocks(p.read_text(), p.name)
    }
    for (w, name, key), body in bodies.items():
        before = bodies.get((w - 1, name, key))
        spec = placeholder_for(name, *key, w)
        if before is None or spec.week == w:
            continue
        changed = fingerprint(before) != fingerprint(body)
        if w in spec.revised_in:
            assert changed, f"{name} {key}: listed as revised in week {w} but unchanged"
        else:
            assert not changed or spec.tunable, f"{name} {key}: changes in week {w}; add it to revised_in"


def _names_stored(code: str) -> set[str]:
    out = set()
    for node in ast.walk(ast.parse(code)):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            out.add(node.id)
        if isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store):
            if isinstance(node.value, ast.Name) and node.value.id == "self":
                out.add(f"self.{node.attr}")
    return out


def _function_end(text: str, line: int) -> int:
    """Last line of the innermost function around `line`."""
    funcs = [
        n
        for n in ast.walk(ast.parse(text))
        if isinstance(n, ast.FunctionDef) and n.lineno < line <= n.end_lineno
    ]
    return max(funcs, key=lambda n: n.lineno).end_lineno


def check_placeholder(spec: Placeholder) -> None:
    """The placeholder parses, has a hint, and sets every name the solution's block sets that the rest of the
    function reads (and every `self.` attribute the solution sets that the file reads elsewhere)."""
    assert spec.hint.strip(), "no hint"
    ast.parse(spec.code)
    sol = ROOT / "solutions" / f"week{spec.week}" / spec.file
    text = sol.read_text()
    lines = text.splitlines()
    [block] = [
        b for b in find_blocks(text, spec.file) if (b.scope, b.occurrence) == (spec.scope, spec.occurrence)
    ]
    rest_of_function = "\n".join(lines[block.end_line : _function_end(text, block.start_line)])
    outside = "\n".join(lines[: block.start_line - 1] + lines[block.end_line :])
    needed = {
        n
        for n in _names_stored(dedent_body(block.body))
        if re.search(rf"(?<![\w.]){re.escape(n)}\b", outside if n.startswith("self.") else rest_of_function)
    }
    missing = needed - _names_stored(spec.code)
    assert not missing, f"{spec.file} {spec.scope}: the placeholder does not set {sorted(missing)}"


@pytest.mark.parametrize("spec", all_blocks(), ids=lambda s: f"{s.file}:{s.scope}:{s.occurrence}")
def test_placeholder_sets_what_the_code_after_it_reads(spec):
    check_placeholder(spec)


def _wrong_placeholders():
    spec = importlib.util.spec_from_file_location("wrong_placeholders", DATA / "wrong_placeholders.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.WRONG


@pytest.mark.parametrize("index", range(4))
def test_wrong_placeholders_are_caught(index):
    with pytest.raises((AssertionError, SyntaxError)):
        check_placeholder(_wrong_placeholders()[index])


def test_generator_refuses_a_block_missing_from_the_table():
    text = "def mystery():\n    # START CODE BLOCK\n    a = 1\n    # END CODE BLOCK\n    return a\n"
    with pytest.raises(BlockError, match="mystery has no entry in simiam/course/placeholders.py") as err:
        stub_text(2, text, "differential_drive.py")
    assert err.value.line == 2


def test_generator_checks_a_week_tag_against_the_table():
    sol = (ROOT / "solutions/week3/go_to_goal.py").read_text()
    tagged = sol.replace("# START CODE BLOCK", "# START CODE BLOCK [week 3]", 1)
    assert stub_text(3, tagged, "go_to_goal.py")[0].count("[week 3]") == 1
    wrong = sol.replace("# START CODE BLOCK", "# START CODE BLOCK [week 4: gains]", 1)
    with pytest.raises(BlockError, match="the START tag says week 4, placeholders.py says week 3"):
        stub_text(3, wrong, "go_to_goal.py")


def test_generator_refuses_a_block_from_a_later_week():
    sol = (ROOT / "solutions/week3/go_to_goal.py").read_text()
    with pytest.raises(BlockError, match="new in week 3"):
        stub_text(2, sol, "go_to_goal.py")


# ---------------------------------------------------------------------------------------------- READMEs


def check_readme(week: int, text: str) -> None:
    """The README names the file and the function of every block new that week, and how to run and grade."""
    from simiam.course.shipped_blocks import SHIPPED

    for file, rows in SHIPPED[week].items():
        for scope, _occ, new_in, _line, _fp in rows:
            if new_in == week:
                assert f"`{file}`" in text or file in text, f"week {week} README does not name {file}"
                assert scope.rsplit(".", 1)[-1] in text, f"week {week} README does not name {scope}"
    for command in (f"simiam run week{week}", f"grade week{week}"):
        assert command in text, f"week {week} README does not say `{command}`"
    if week > 2:
        assert f"simiam migrate week{week} --from" in text


@pytest.mark.parametrize("week", WEEKS)
def test_readme_says_what_to_write_and_how_to_check_it(week):
    check_readme(week, (ROOT / "assignments" / f"week{week}" / "README.md").read_text())


def test_incomplete_readme_is_caught():
    text = (ROOT / "assignments/week4/README.md").read_text()
    with pytest.raises(AssertionError, match="apply_sensor_geometry"):
        check_readme(4, text.replace("apply_sensor_geometry", "the geometry"))
    with pytest.raises(AssertionError, match="grade week3"):
        check_readme(3, (ROOT / "assignments/week3/README.md").read_text().replace("grade week3", "grade it"))


# ------------------------------------------------------------------------- the packaged skeletons (issue 11)


def test_packaged_skeletons_are_the_stubs_with_every_block_a_placeholder():
    """What the grader splices into (package data) is what students receive in assignments/ outside the
    blocks, line for line, and holds only placeholders inside them: no solution code of any week."""
    from simiam.course.skeletons import skeleton_files

    for week in WEEKS:
        skeletons = skeleton_files(week)
        stubs = {p.name: p.read_text() for p in (ROOT / "assignments" / f"week{week}").glob("*.py")}
        assert sorted(skeletons) == sorted(stubs)
        for name, skeleton in skeletons.items():
            result = splice(skeleton, stubs[name], name)
            assert not result.errors and not result.outside_edits and result.text == stubs[name]
            for b in find_blocks(skeleton, name):
                spec = placeholder_for(name, b.scope, b.occurrence, week)
                assert b.body == spec.body(b.indent), f"week{week}/{name} {b.describe()} is not a placeholder"


def test_skeleton_drift_is_detected(tmp_path):
    """A skeleton edited by hand or left behind is caught, and `write` puts it back / removes it."""
    generated = generate()
    write(generated, tmp_path)
    skel = tmp_path / "simiam/course/skeletons/week3/go_to_goal.py"
    skel.write_text(skel.read_text().replace("self.E_k = 0", "self.E_k = 1"))
    (tmp_path / "simiam/course/skeletons/week4/old.py").write_text("x = 1\n")
    assert differences(generated, tmp_path) == [
        "simiam/course/skeletons/week3/go_to_goal.py",
        "simiam/course/skeletons/week4/old.py (no longer in solutions/)",
    ]
    write(generated, tmp_path)
    assert differences(generated, tmp_path) == []
