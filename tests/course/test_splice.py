"""Splicing a submission's blocks into the pristine stub: the grader's trust boundary.

Each property is written as a check that takes a splice function; the real one passes every check and each
wrong implementation in tests/data/blocks/wrong_splicers.py fails the check written against it.
"""

import ast
import importlib.util
import os
from pathlib import Path

import pytest

from simiam.course.blocks import find_blocks
from simiam.course.splice import splice, splice_folder

DATA = Path(__file__).parents[1] / "data" / "blocks"
STUB = (DATA / "stub.py").read_text()
GOOD = (DATA / "good.py").read_text()


def read(name: str) -> str:
    return (DATA / name).read_text()


def _wrong():
    spec = importlib.util.spec_from_file_location("wrong_splicers", DATA / "wrong_splicers.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.WRONG


def bodies(text: str) -> dict:
    """Block bodies (as ASTs) by function and START tag: the identity of a block, whatever its position."""
    return {(b.scope, b.tag): ast.dump(ast.parse(b.body.strip() + "\n")) for b in find_blocks(text, "x.py")}


def same_code(a: str, b: str) -> bool:
    return ast.dump(ast.parse(a)) == ast.dump(ast.parse(b))


# ---------------------------------------------------------------------- checks (a splice function each)


def check_reordered(fn) -> None:
    """Functions moved around: each body still lands in its own function."""
    result = fn(STUB, read("reordered.py"), "controller.py")
    assert bodies(result.text) == bodies(read("reordered.py"))


def check_reindented(fn) -> None:
    """A file re-indented to 2 spaces, and bodies indented deeper or with tabs, splice to the same code."""
    for name in ("reindented.py", "deeper_and_tabs.py"):
        result = fn(STUB, read(name), "controller.py")
        assert same_code(result.text, GOOD), name
        assert not result.errors


def check_outside_not_run(fn) -> None:
    """Edits outside the blocks are reported, never taken."""
    result = fn(STUB, read("outside_edits.py"), "controller.py")
    assert "import os" not in result.text and "10 * self.Kp" not in result.text
    assert same_code(result.text, GOOD)
    assert [(e.first_line, e.last_line) for e in result.outside_edits] == [(4, 4), (23, 23)]


def check_swallow(fn) -> None:
    """A body that opens a string or a bracket cannot eat the stub's code after it."""
    for name in ("swallow.py", "open_bracket.py"):
        result = fn(STUB, read(name), "controller.py")
        assert "self.theta_g = theta_g" in result.text
        compile(result.text, "controller.py", "exec")
        assert [(e.line, "syntax error" in e.message) for e in result.errors] == [(16, True)], name
        assert "Steer.execute" not in result.blocks_taken


def check_form_feed(fn) -> None:
    """A form feed (or other odd whitespace) in a block's indentation is refused with file and line: Python
    resets the column at a form feed, so the line would leave its function and run at module level."""
    result = fn(STUB, read("form_feed.py"), "controller.py")
    namespace: dict = {}
    exec(compile(result.text, "controller.py", "exec"), namespace)
    assert namespace["wheel_speed"](1.0, 0.5) == 0.0          # the stub's placeholder, not the student's 99
    assert [(e.file, e.line) for e in result.errors] == [("controller.py", 31)]
    assert "form feed" in result.errors[0].message and "wheel_speed" in result.errors[0].message


CHECKS = [check_reordered, check_reindented, check_outside_not_run, check_swallow, check_form_feed]
CAUGHT_BY = {
    "by_ordinal": check_reordered,
    "no_reindent": check_reindented,
    "whole_file": check_outside_not_run,
    "no_syntax_check": check_swallow,
    "no_whitespace_check": check_form_feed,
}


@pytest.mark.parametrize("check", CHECKS, ids=lambda c: c.__name__)
def test_real_splice_passes(check):
    check(splice)


@pytest.mark.parametrize("name", sorted(CAUGHT_BY))
def test_wrong_splice_is_caught(name):
    with pytest.raises((AssertionError, SyntaxError)):
        CAUGHT_BY[name](_wrong()[name])


# ----------------------------------------------------------------------------------------- direct cases


def test_good_submission_gives_back_the_submission():
    result = splice(STUB, GOOD, "controller.py")
    assert result.text == GOOD
    assert result.ok and not result.outside_edits
    assert result.blocks_taken == [
        "Steer.__init__",
        "Steer.execute",
        "Steer.execute (block 2)",
        "wheel_speed",
    ]


def test_syntax_error_names_the_line_and_keeps_the_placeholder():
    result = splice(STUB, read("syntax_error.py"), "controller.py")
    [err] = result.errors
    assert (err.file, err.line) == ("controller.py", 18)
    assert "syntax error in the code block of Steer.execute (block 2)" in err.message
    assert "never closed" in err.message
    assert result.blocks_kept == ["Steer.execute (block 2)"]
    assert "        e_k = 0.0\n" in result.text  # the stub's placeholder
    assert "math.atan2(y_g - y, x_g - x)" in result.text  # the other blocks were taken


@pytest.mark.parametrize(
    "fixture, line, words",
    [
        (
            "deleted_end.py",
            16,
            ["inside the block opened at line 14", "no block of this file can be taken"],
        ),
        ("nested.py", 10, ["inside the block opened at line 8"]),
        ("duplicated_start.py", 27, ["inside the block opened at line 26"]),
        ("duplicated_block.py", 17, ["Steer.execute has 3 code blocks, the stub has 2", "duplicated"]),
        ("deleted_markers.py", 7, ["Steer.__init__ has 0 code block(s), the stub has 1", "deleted"]),
    ],
)
def test_broken_markers(fixture, line, words):
    result = splice(STUB, read(fixture), "controller.py")
    assert result.errors, fixture
    err = result.errors[0]
    assert (err.file, err.line) == ("controller.py", line)
    for w in words:
        assert w in err.message
    compile(result.text, "controller.py", "exec")


def test_duplicated_block_keeps_only_that_function_from_the_stub():
    result = splice(STUB, read("duplicated_block.py"), "controller.py")
    assert result.blocks_taken == ["Steer.__init__", "wheel_speed"]
    assert "self.Kp = 4.0" in result.text and "theta_g = 0.0" in result.text


def test_block_in_a_function_the_stub_does_not_have():
    sub = GOOD + "\n\ndef extra():\n    # START CODE BLOCK\n    import os\n    # END CODE BLOCK\n"
    result = splice(STUB, sub, "controller.py")
    assert [(e.line, "where the stub has none" in e.message) for e in result.errors] == [(36, True)]
    assert "import os" not in result.text


def test_reindented_file_reports_no_outside_edits():
    result = splice(STUB, read("reindented.py"), "controller.py")
    assert result.outside_edits == []


# ---------------------------------------------------------------------------------------------- folders


@pytest.fixture
def folders(tmp_path):
    stub, sub, out = tmp_path / "stub", tmp_path / "sub", tmp_path / "out"
    stub.mkdir()
    sub.mkdir()
    (stub / "controller.py").write_text(STUB)
    (stub / "other.py").write_text(
        "def g():\n    # START CODE BLOCK\n    y = 0\n    # END CODE BLOCK\n    return y\n"
    )
    (stub / "README.md").write_text("not code")
    return stub, sub, out


def test_splice_folder(folders):
    stub, sub, out = folders
    (sub / "controller.py").write_text(read("syntax_error.py"))
    (sub / "mine.py").write_text("print('hi')\n")
    report = splice_folder(stub, sub, out)
    assert sorted(p.name for p in out.iterdir()) == ["controller.py", "other.py"]
    assert report.missing_files == ["other.py"]
    assert (out / "other.py").read_text() == (stub / "other.py").read_text()
    assert report.extra_files == ["mine.py"]
    assert not report.ok
    msgs = report.messages()
    assert msgs[0] == "other.py: file missing from the submission; the stub's version is used"
    assert msgs[1].startswith("controller.py:18: syntax error")
    assert msgs[2] == "mine.py: not part of the assignment (ignored)"
    assert report.to_json()["files"]["controller.py"]["errors"][0]["line"] == 18


def test_splice_folder_does_not_follow_links(folders, tmp_path):
    stub, sub, out = folders
    secret = tmp_path / "secret.py"
    secret.write_text(GOOD)
    os.symlink(secret, sub / "controller.py")
    report = splice_folder(stub, sub, out)
    [err] = report.files["controller.py"].errors
    assert "not a regular file" in err.message
    assert (out / "controller.py").read_text() == STUB


def test_splice_folder_refuses_binary_and_huge_files(folders):
    stub, sub, out = folders
    (sub / "controller.py").write_bytes(b"x = 1\n# \xff\xfe\n")
    (sub / "other.py").write_text("#" * 300_000)
    report = splice_folder(stub, sub, out)
    assert str(report.files["controller.py"].errors[0]) == "controller.py:2: not valid UTF-8 text"
    assert "more than the" in report.files["other.py"].errors[0].message


def test_outside_edit_message_is_one_line_with_the_change():
    result = splice(STUB, read("outside_edits.py"), "controller.py")
    assert (
        str(result.outside_edits[0])
        == "controller.py:4: changed outside the code blocks (not used): + import os"
    )
    assert "\n" not in str(result.outside_edits[1])
    assert result.outside_edits[1].diff.splitlines()[1].startswith("+        return 10 * self.Kp")


def _reindent(text: str, width: int, tabs: bool) -> str:
    """Every 4 columns of indentation become `width` spaces (or one tab)."""
    out = []
    for line in text.splitlines(keepends=True):
        lead = len(line) - len(line.lstrip(" "))
        out.append(("\t" if tabs else " " * width) * (lead // 4) + line[lead:])
    return "".join(out)


@pytest.mark.parametrize("width", [1, 2, 3, 8])
@pytest.mark.parametrize("tabs", [False, True])
def test_any_consistent_indentation_splices_to_the_same_code(width, tabs):
    result = splice(STUB, _reindent(GOOD, width, tabs), "controller.py")
    assert not result.errors
    assert same_code(result.text, GOOD)
    assert result.outside_edits == []


def test_markers_moved_to_column_0_still_match():
    sub = GOOD.replace(
        "        # START CODE BLOCK [week 3: gains]", "# START CODE BLOCK [week 3: gains]"
    ).replace("        # END CODE BLOCK\n        self.E_k", "# END CODE BLOCK\n        self.E_k")
    assert sub.count("\n# START CODE BLOCK") == 1
    result = splice(STUB, sub, "controller.py")
    assert not result.errors
    assert same_code(result.text, GOOD)


def test_windows_line_endings_and_bom():
    sub = "\ufeff" + GOOD.replace("\n", "\r\n")
    result = splice(STUB, sub.lstrip("\ufeff"), "controller.py")
    assert not result.errors and result.outside_edits == []
    assert same_code(result.text, GOOD)


def test_splice_folder_reads_a_bom_and_crlf(folders):
    stub, sub, out = folders
    (sub / "controller.py").write_bytes(b"\xef\xbb\xbf" + GOOD.replace("\n", "\r\n").encode())
    report = splice_folder(stub, sub, out)
    assert report.files["controller.py"].blocks_taken == [
        "Steer.__init__",
        "Steer.execute",
        "Steer.execute (block 2)",
        "wheel_speed",
    ]
    assert same_code((out / "controller.py").read_text(), GOOD)


def test_lines_are_counted_as_python_counts_them():
    """A form feed or a Unicode line separator is not a new line: no fake marker, no shifted line numbers."""
    sub = GOOD.replace(
        "        self.Kp = 4.0\n", '        self.Kp = 4.0\n        s = "\u2028# END CODE BLOCK"\n\x0c\n'
    )
    sub = sub.replace("        e_k = theta_g - theta\n", "        e_k = (theta_g - theta\n")
    result = splice(STUB, sub, "controller.py")
    assert "Steer.__init__" in result.blocks_taken
    assert [(e.line, "never closed" in e.message) for e in result.errors] == [(20, True)]


def test_hostile_sizes_are_refused_or_summarised():
    # a huge file: blocks still taken (scopes read from indentation), the outside diff is one summary line
    result = splice(STUB, GOOD + "x = 1\n" * 20000, "controller.py")
    assert len(result.blocks_taken) == 4
    [edit] = result.outside_edits
    assert (edit.first_line, "20024 lines outside the blocks, the stub has 24" in edit.diff) == (1, True)
    # thousands of blocks: refused at the first one too many
    many = GOOD + "def f():\n" + "    # START CODE BLOCK\n    # END CODE BLOCK\n" * 300
    assert "more than 200 code blocks" in str(splice(STUB, many, "controller.py").errors[0])
    # absurdly nested or NUL bytes: an error for that block, the stub's code instead
    for body in ("-" * 100_000 + "1", "4.0\x00"):
        result = splice(STUB, GOOD.replace("self.Kp = 4.0", f"self.Kp = {body}"), "controller.py")
        assert [e.line for e in result.errors] in ([8], [9]) and "Steer.__init__" in result.blocks_kept


@pytest.mark.parametrize("char, name", [("\f", "form feed"), ("\v", "vertical tab"), ("\u00a0", "U+00A0"),
                                        ("\u3000", "U+3000")])
def test_odd_whitespace_in_indentation_is_named(char, name):
    from simiam.course.splice import odd_indent

    assert odd_indent(f"    x = 1\n    {char}y = 2\n") == (2, odd_indent(f"{char}y")[1])
    assert name in odd_indent(f"{char}y")[1]
    assert odd_indent("    x = 1\n\f\n\t y = 2\n") is None       # a page break on a blank line is harmless
