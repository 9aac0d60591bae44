"""Issue 30 item 7: `grade selfcheck` on hostile wrong versions (tests/data/attacks/selfcheck/): a patch
naming `..`, a patch that is not UTF-8, a folder named `x.patch`, a patch of a week the course does not
have. Each once ended selfcheck with a traceback before anything was graded; now each is its own FAIL line
naming the problem, and the rest of the selfcheck runs."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from mistakes import DATA, ROOT

from grader.platforms.selfcheck import run_selfcheck

HOSTILE = DATA / "attacks" / "selfcheck"
SAYS = {"dotdot": "want '--- a/solutions/weekN/F'", "not_utf8": "not UTF-8 text",
        "x": "not a file", "no_such_week": "solutions/week9 does not exist"}


def _selfcheck(wrong: Path) -> list[str]:
    lines: list[str] = []
    assert run_selfcheck(ROOT, [1], wrong=wrong, out=lines.append) == 1, "\n".join(lines)
    return lines


@pytest.mark.parametrize("name", sorted(SAYS))
def test_each_hostile_wrong_version_is_its_own_fail_line(tmp_path: Path, name: str) -> None:
    wrong = tmp_path / "wrong"
    wrong.mkdir()
    source = HOSTILE / f"{name}.patch"
    (shutil.copytree if source.is_dir() else shutil.copy)(source, wrong / source.name)
    lines = _selfcheck(wrong)
    fails = [ln for ln in lines if ln.startswith("FAIL")]
    assert len(fails) == 1 and fails[0].startswith(f"FAIL  wrong {name}: ") and SAYS[name] in fails[0], lines
    assert "ok    solutions week1 (hidden checks included)  [2/2]" in lines   # and the selfcheck went on
    assert lines[-1] == "selfcheck: 1 failed"


def test_all_of_them_together_each_get_a_line(tmp_path: Path) -> None:
    lines = _selfcheck(HOSTILE)
    assert sorted(ln.split(":")[0] for ln in lines if ln.startswith("FAIL")) == [
        f"FAIL  wrong {name}" for name in sorted(SAYS)], lines
    assert lines[-1] == f"selfcheck: {len(SAYS)} failed"
    assert sorted(p.name for p in HOSTILE.iterdir()) == ["dotdot.patch", "no_such_week.patch",
                                                         "not_utf8.patch", "x.patch"]
