"""Parsing START/END code blocks: names, lines, tolerated spellings, and errors with file and line."""

from pathlib import Path

import pytest

from simiam.course.blocks import BlockError, dedent_body, find_blocks, fingerprint

DATA = Path(__file__).parents[1] / "data" / "blocks"


def read(name: str) -> str:
    return (DATA / name).read_text()


def test_blocks_are_named_by_scope_and_position():
    blocks = find_blocks(read("stub.py"), "controller.py")
    got = [(b.ordinal, b.scope, b.occurrence, b.start_line, b.end_line, b.week) for b in blocks]
    assert got == [
        (1, "Steer.__init__", 1, 8, 10, 3),
        (2, "Steer.execute", 1, 14, 16, 3),
        (3, "Steer.execute", 2, 17, 19, 3),
        (4, "wheel_speed", 1, 25, 27, None),
    ]
    assert blocks[1].tag == "[week 3: theta_g]"
    assert blocks[0].body == "        self.Kp = 0.0\n"


def test_tolerated_marker_spellings():
    text = (
        "def f():\n"
        "    #START CODE BLOCK (theta_g)   \n"
        "    a = 1\n"
        "    # end code block %%\t\n"
        "    ## START  CODE  BLOCK\n"
        "    b = 2\n"
        "    #   END CODE BLOCK\n"
    )
    blocks = find_blocks(text, "f.py")
    assert [(b.start_line, b.end_line, b.tag) for b in blocks] == [(2, 4, "(theta_g)"), (5, 7, "")]


def test_marker_after_code_on_the_same_line_is_not_a_marker():
    text = "def f():\n    a = 1  # START CODE BLOCK\n    return a\n"
    assert find_blocks(text, "f.py") == []


@pytest.mark.parametrize(
    "fixture, line, words",
    [
        (
            "deleted_end.py",
            16,
            ["START CODE BLOCK inside the block opened at line 14", "END CODE BLOCK missing"],
        ),
        ("nested.py", 10, ["START CODE BLOCK inside the block opened at line 8"]),
        ("duplicated_start.py", 27, ["START CODE BLOCK inside the block opened at line 26"]),
    ],
)
def test_unbalanced_markers_name_file_and_line(fixture, line, words):
    with pytest.raises(BlockError) as err:
        find_blocks(read(fixture), "controller.py")
    assert err.value.file == "controller.py" and err.value.line == line
    assert str(err.value).startswith(f"controller.py:{line}: ")
    for w in words:
        assert w in str(err.value)


def test_end_without_start_and_start_without_end():
    with pytest.raises(BlockError, match=r"^f\.py:3: END CODE BLOCK without a START"):
        find_blocks("def f():\n    a = 1\n    # END CODE BLOCK\n", "f.py")
    with pytest.raises(BlockError, match=r"^f\.py:2: START CODE BLOCK has no END"):
        find_blocks("def f():\n    # START CODE BLOCK\n    a = 1\n", "f.py")


def test_scope_found_when_the_file_does_not_parse():
    # A broken line outside the blocks: the scope comes from indentation instead of the AST.
    text = read("good.py").replace("        self.E_k = 0.0\n", "        self.E_k = = 0.0\n")
    blocks = find_blocks(text, "controller.py")
    assert [b.scope for b in blocks] == ["Steer.__init__", "Steer.execute", "Steer.execute", "wheel_speed"]


def test_scope_of_a_block_whose_body_does_not_parse():
    blocks = find_blocks(read("swallow.py"), "controller.py")
    assert [b.key for b in blocks][1] == ("Steer.execute", 1)


def test_dedent_body_handles_tabs_and_shallow_comments():
    body = "\t\tif a:\n# a comment at column 0\n\t\t\tb = 1\n\n"
    assert dedent_body(body) == "if a:\n# a comment at column 0\n        b = 1\n\n"


def test_fingerprint_ignores_comments_and_layout_but_not_code():
    a = fingerprint("    x = 1  # one\n\n    y = 2\n")
    assert a == fingerprint("x = 1\n# a comment\ny = 2\n")
    assert a != fingerprint("x = 1\ny = 3\n")
    assert fingerprint("x = (\n") is None
