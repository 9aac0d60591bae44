"""Every wrong version kept as a patch still applies to the current solutions/ (a solution change cannot
silently orphan one), changes something, and the applier refuses what does not fit exactly."""

from __future__ import annotations

from pathlib import Path

import pytest
from mistakes import ROOT, MistakeError, all_mistakes, apply_hunks, build, mistake_path, read_mistake

MISTAKES = all_mistakes()


def test_the_mistakes_are_found():
    kinds = {kind for kind, _ in MISTAKES}
    assert kinds == {"wrong", "submissions", "stuck", "attacks/graded"} and len(MISTAKES) >= 60


@pytest.mark.parametrize(("kind", "name"), MISTAKES, ids=[f"{k}/{n}" for k, n in MISTAKES])
def test_each_mistake_applies_to_the_current_solution_and_changes_it(tmp_path: Path, kind: str, name: str):
    mistake = read_mistake(mistake_path(kind, name))
    assert mistake.why.startswith(f"{name}: ") and len(mistake.why) > len(name) + 5
    folder = build(kind, name, tmp_path)
    solution = ROOT / "solutions" / f"week{mistake.week}"
    for file in mistake.files:
        assert (folder / file).read_text() != (solution / file).read_text(), f"{kind}/{name} changes nothing"
    untouched = {p.name for p in solution.glob("*.py")} - set(mistake.files)
    assert untouched and all((folder / f).read_bytes() == (solution / f).read_bytes() for f in untouched)


def _one_hunk(patch_text: str, tmp_path: Path):
    path = tmp_path / "m.patch"
    path.write_text(patch_text)
    return read_mistake(path).files["go_to_goal.py"]


PATCH = """# m: two lines become one
--- a/solutions/week3/go_to_goal.py
+++ b/solutions/week3/go_to_goal.py
@@ -2,3 +2,2 @@
 b
-c
-d
+cd
"""


def test_a_hunk_applies_at_its_line_or_once_elsewhere(tmp_path: Path):
    hunks = _one_hunk(PATCH, tmp_path)
    assert apply_hunks("a\nb\nc\nd\ne\n", hunks, "x") == "a\nb\ncd\ne\n"
    assert apply_hunks("z\nz\na\nb\nc\nd\n", hunks, "x") == "z\nz\na\nb\ncd\n"  # moved: found once


@pytest.mark.parametrize("text", ["a\nb\nC\nd\n", "a\nb\nc\n", "b\nc\nd\nb\nc\nd\n"],
                         ids=["changed", "shortened", "ambiguous"])
def test_a_hunk_that_does_not_fit_exactly_is_refused(tmp_path: Path, text: str):
    hunks = _one_hunk(PATCH, tmp_path)
    with pytest.raises(MistakeError, match="x: hunk @@ -2,3 \\+2,2 @@ does not apply"):
        apply_hunks(text, hunks, "x")


@pytest.mark.parametrize("bad", [
    PATCH.replace("# m: two lines become one\n", ""),           # no title
    PATCH.replace("@@ -2,3 +2,2 @@", "@@ -2,4 +2,2 @@"),         # counts do not match the body
    PATCH.replace("+++ b/solutions/week3", "+++ b/solutions/week4"),  # two different files
    PATCH.replace(" b\n", "?b\n"),                                # not a diff line
])
def test_a_malformed_patch_is_refused(tmp_path: Path, bad: str):
    with pytest.raises(MistakeError):
        _one_hunk(bad, tmp_path)


def test_a_mistake_that_no_longer_applies_fails_the_build(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    data = tmp_path / "data"
    (data / "wrong").mkdir(parents=True)
    (data / "wrong" / "stale.patch").write_text(PATCH)  # go_to_goal.py has no 'b, c, d' lines
    monkeypatch.setattr("mistakes.DATA", data)
    with pytest.raises(MistakeError, match="stale.patch on solutions/week3/go_to_goal.py: hunk"):
        build("wrong", "stale", tmp_path / "out")
