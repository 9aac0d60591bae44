"""Each handout agrees with itself (issue 31): a placeholder a file's docstring quotes is the code its stub
really holds, and week 3's part numbers are the same in the README's table, the TODO hints and the
go_to_goal.py docstring."""

from __future__ import annotations

import ast
import re
from pathlib import Path

from simiam.course.weeks import all_weeks

ROOT = Path(__file__).resolve().parents[2]
ASSIGNMENT = re.compile(r"`((?:self\.)?[A-Za-z_]\w*) = ([^`]+)`")


def _placeholder_values() -> dict[tuple[str, str], set[str]]:
    """{(file, name): every value a declared placeholder assigns to that name in that file}."""
    out: dict[tuple[str, str], set[str]] = {}
    for week in all_weeks():
        for block in week.blocks:
            for line in block.code.splitlines():
                name, eq, value = line.partition(" = ")
                if eq:
                    out.setdefault((block.file, name.strip()), set()).add(value.split("  #")[0].strip())
    return out


def _quoted_placeholders(text: str) -> list[tuple[str, str]]:
    return [(m.group(1), m.group(2).strip()) for m in ASSIGNMENT.finditer(" ".join(text.split()))]


def test_every_placeholder_a_docstring_quotes_is_the_stubs() -> None:
    values = _placeholder_values()
    wrong, seen = [], 0
    for path in sorted((ROOT / "assignments").glob("week*/*.py")):
        doc = ast.get_docstring(ast.parse(path.read_text())) or ""
        for name, value in _quoted_placeholders(doc):
            known = values.get((path.name, name))
            if known is None:
                continue
            seen += 1
            if value not in known:
                wrong.append(f"{path.relative_to(ROOT)}: `{name} = {value}`, the stub has {sorted(known)}")
    assert seen > 20, seen  # the docstrings do quote their placeholders
    assert not wrong, "\n".join(wrong)


def test_the_test_sees_a_placeholder_quoted_wrong() -> None:
    """The week-6 docstring's `self.d_fw = 0.1` where the stub holds `self.d_fw = 0`."""
    values = _placeholder_values()
    (name, value), = _quoted_placeholders("Placeholder: `self.d_fw = 0.1` and")
    assert value not in values[("qb_supervisor.py", name)]


ORDINAL = {1: "1st", 2: "2nd", 3: "3rd"}


def _readme_parts(week: int) -> dict[tuple[str, str, int], int]:
    """{(file, scope, occurrence): part} from the README's table rows `| part | file | block | ... |`."""
    out = {}
    readme = (ROOT / "assignments" / f"week{week}" / "README.md").read_text()
    for part, file, block in re.findall(r"^\| (\d) \| `([\w.]+)` \| ([^|]+) \|", readme, re.M):
        scope = re.search(r"`([\w.]+)`", block).group(1)
        n = re.match(r"(\d)\w\w block", block.strip())
        out[(file, scope, int(n.group(1)) if n else 1)] = int(part)
    return out


def test_week3_parts_are_numbered_alike_in_readme_todos_and_docstring() -> None:
    week3 = next(w for w in all_weeks() if w.number == 3)
    table = _readme_parts(3)
    assert len(table) == len(week3.blocks) == 5, table
    doc = " ".join((ast.get_docstring(ast.parse((ROOT / "assignments/week3/go_to_goal.py").read_text()))
                    or "").split())
    for block in week3.blocks:
        part = table[block.key]
        assert f"part {part})" in block.hint or f"part {part}):" in block.hint, (block.key, part, block.hint)
        if block.file != "go_to_goal.py":
            continue
        where = ("__init__ gains" if block.scope.endswith("__init__")
                 else f"({ORDINAL[block.occurrence]} block of execute)")
        said = re.findall(r"[pP]art (\d)[^.;]*?" + re.escape(where), doc)
        assert said == [str(part)], (block.key, part, where, doc)
