"""docs/platforms.md walks an instructor through each platform: every command it shows parses, and it
covers each platform and the self-check."""

from __future__ import annotations

import re
import shlex

import pytest
from mistakes import ROOT

from grader.platforms.cli import COMMANDS, _parser

DOC = (ROOT / "docs" / "platforms.md").read_text()
BLOCKS = re.findall(r"```bash\n(.*?)```", DOC, re.S)
COMMAND_LINES = sorted({ln.split("  #")[0].strip() for block in BLOCKS for ln in block.splitlines()
                        if ln.strip().startswith("grade ")})


def test_the_doc_shows_every_instructor_command():
    assert {shlex.split(ln)[1] for ln in COMMAND_LINES} == set(COMMANDS)
    for heading in ("## 0. Check the course first", "## 1. Release a week", "## 2. Gradescope",
                    "## 3. PrairieLearn", "## 4. Coursera"):
        assert heading in DOC


@pytest.mark.parametrize("line", COMMAND_LINES)
def test_every_command_the_doc_shows_parses(line: str):
    words = shlex.split(line)
    _parser().parse_args(words[1:])
