"""find_blocks keeps its work per text (issue 24): a caller gets its own list every time, an error is raised
again every time, and a text longer than the kept size is found afresh (a batch of hostile files cannot
fill the grading process's memory through the cache)."""

from __future__ import annotations

import pytest

from simiam.course import blocks
from simiam.course.blocks import BlockError, find_blocks

TEXT = "def f():\n    # START CODE BLOCK\n    x = 1\n    # END CODE BLOCK\n    return x\n"


def test_each_caller_gets_its_own_list_of_the_same_blocks():
    first = find_blocks(TEXT, "f.py")
    first.clear()  # a caller may change its list
    again = find_blocks(TEXT, "f.py")
    assert [b.scope for b in again] == ["f"] and again[0].body == "    x = 1\n"


def test_an_unbalanced_text_raises_every_time():
    for _ in range(2):
        with pytest.raises(BlockError, match="no END CODE BLOCK"):
            find_blocks("# START CODE BLOCK\n", "g.py")


def test_a_long_text_is_not_kept():
    long = TEXT + "# " + "x" * blocks._KEPT_TEXT + "\n"
    blocks._kept_blocks.cache_clear()  # (only what this test keeps is counted)
    assert [b.scope for b in find_blocks(long, "h.py")] == ["f"]
    assert blocks._kept_blocks.cache_info().currsize == 0  # found afresh, nothing kept
    find_blocks(TEXT + "# short\n", "h.py")
    assert blocks._kept_blocks.cache_info().currsize == 1
