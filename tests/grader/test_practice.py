"""`grade weekN --practice` (issue 31): the hidden checks of weeks 3-7 run on a practice set that ships with
the package (grader/practice/weekN.json), drawn as the hidden variants are but never one of them, vetted with
their margins, and shown apart from the grade.

Week 3's hidden goals are drawn from the seed, on the 0.01 m grid (grader.checks.week3: every coordinate
rounded to 2 decimals, start headings too): its practice goals and starts lie on that grid shifted by
0.005, so no seed can ever draw one, and no seed's draw had to change (excluding practice goals from the
draw would have changed the goals of every seed that drew one, and so earlier official grades)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import mistakes
import pytest

from grader.checks.week3 import seeded_goals, seeded_start_and_goal
from grader.cli import main
from grader.hidden import load_hidden
from grader.hidden.draw import turn_quarter
from grader.practice import WEEKS_WITH_PRACTICE, load_practice

ROOT = Path(__file__).resolve().parents[2]


def _angle(turn: int, of: int) -> float:
    """A turn of turn/of of a full turn, in degrees, comparable across `of` (1/24 == 2/48)."""
    return round(360.0 * turn / of % 360.0, 9)


def same_variant(week: int, a: dict, b: dict) -> bool:
    """Whether two variants of `week` run the same scenario, however they are written."""
    def near(x: list, y: list) -> bool:
        return len(x) == len(y) and all(math.isclose(p, q, abs_tol=1e-9) for p, q in zip(x, y, strict=True))

    if week == 4:
        return _angle(a["turn"], a["of"]) == _angle(b["turn"], b["of"]) and a["mirror"] == b["mirror"]
    if week == 5:
        return a["mode"] == b["mode"] and near(a["start"], b["start"]) and near(a["goal"], b["goal"])
    if week == 6:
        return (a["direction"] == b["direction"] and near([a["d_fw"]], [b["d_fw"]])
                and math.isclose(a["theta0"] % (2 * math.pi), b["theta0"] % (2 * math.pi), abs_tol=1e-9))
    if week == 7:
        return _angle(a["turn"], a["of"]) == _angle(b["turn"], b["of"]) and near(a["goal"], b["goal"])
    raise ValueError(f"week {week}: its hidden variants are drawn per seed (see on_a_seeds_grid)")


def twins(week: int, practice: list[dict], hidden: list[dict]) -> list[dict]:
    """The practice variants that are hidden ones."""
    return [p for p in practice if any(same_variant(week, p, h) for h in hidden)]


def on_a_seeds_grid(value: float) -> bool:
    """Whether a seed's week-3 draw can give `value`: every one is rounded to 2 decimals."""
    return round(value, 2) == value


@pytest.mark.parametrize("week", [4, 5, 6, 7])
def test_no_practice_variant_is_a_hidden_one(week: int) -> None:
    practice, hidden = load_practice(week), load_hidden(week)
    assert practice is not None and hidden is not None
    assert twins(week, practice["variants"], hidden["variants"]) == []


@pytest.mark.parametrize("week", [4, 5, 6, 7])
def test_a_hidden_variant_planted_in_the_practice_set_is_found(week: int) -> None:
    """The test above can fail: a hidden variant, written another way where it can be, is found."""
    planted = dict(load_hidden(week)["variants"][-1])
    if "turn" in planted:  # the same heading in 48ths
        planted["turn"], planted["of"] = planted["turn"] * 48 // planted["of"], 48
    if "theta0" in planted:
        planted["theta0"] += 2 * math.pi
    practice = [*load_practice(week)["variants"], planted]
    assert twins(week, practice, load_hidden(week)["variants"]) == [planted]


def test_no_seed_can_draw_a_week3_practice_variant() -> None:
    variants = load_practice(3)["variants"]
    coordinates = [c for v in variants for c in [*v["goal"], *v.get("start", [])]]
    assert coordinates and not [c for c in coordinates if on_a_seeds_grid(c)], variants
    # the premise: whatever the seed, its goals and starts are on the grid
    for seed in [2014, *range(40)]:
        start, goal = seeded_start_and_goal(seed, "hidden")
        drawn = [*start, *goal, *(c for g in seeded_goals(seed, 2, "hidden") for c in g)]
        assert all(on_a_seeds_grid(c) for c in drawn), (seed, drawn)
    assert on_a_seeds_grid(0.74) and not on_a_seeds_grid(0.745)  # a goal on the grid would be found


def test_each_week_3_to_7_has_a_practice_set_spread_over_the_draws_kinds() -> None:
    assert WEEKS_WITH_PRACTICE == (3, 4, 5, 6, 7)
    sets = {week: load_practice(week)["variants"] for week in WEEKS_WITH_PRACTICE}
    assert all(4 <= len(v) <= 8 for v in sets.values()), {w: len(v) for w, v in sets.items()}
    assert {v["check"] for v in sets[3]} == {"other_goals", "tracking_other_goal"}
    assert any("start" in v for v in sets[3])  # a start away from the origin, as the hidden check has
    assert {v["mode"] for v in sets[5]} == {"blending", "switching"}
    assert {v["direction"] for v in sets[6]} == {"left", "right"}
    assert {v["mirror"] for v in sets[4]} == {False, True}
    assert len({turn_quarter(v["turn"], v["of"]) for v in sets[4]}) >= 3
    assert len({turn_quarter(v["turn"], v["of"]) for v in sets[7]}) >= 2


def _grade(capsys, tmp_path: Path, *argv: str) -> tuple[int, str, dict]:
    out = tmp_path / "out"
    code = main([*argv, "--out", str(out)])
    said = " ".join(capsys.readouterr().out.split())  # unwrapped
    result = json.loads(next(out.glob("week*.json")).read_text()) if out.is_dir() else {}
    return code, said, result


def test_practice_on_the_reference_passes_apart_from_the_grade(capsys, tmp_path: Path) -> None:
    code, said, result = _grade(capsys, tmp_path, "week4", "--solutions", "--practice")
    assert code == 0, said
    (check,) = result["practice"]["checks"]
    assert check["id"] == "week4.avoid.other_starts" and check["status"] == "passed", check
    assert check["visibility"] == "practice" and "points" not in check and "max_points" not in check
    assert check["name"] == "30 s in variants of the week-4 world of the practice set"
    assert "week4.avoid.other_starts" not in [c["id"] for c in result["checks"]]
    assert result["score"] == result["max_score"] == 7.5  # the visible checks only
    assert result["hidden"] is False
    assert result["practice"]["variants"] == load_practice(4)["variants"]
    assert "practice (not graded): the hidden checks on 6 practice variants" in said
    assert "Official grading runs the same checks on other variants" in said
    assert "turned 352.5 degrees: no collision" in said  # the variants that ran are named


def test_practice_catches_what_only_hidden_like_variants_catch(capsys, tmp_path: Path) -> None:
    """Unit gains (tests/data/submissions/week4_unit_gains.patch, a real student's): every visible check
    passes, a practice variant collides; the command fails naming it, the grade stays whole."""
    folder = mistakes.build("submissions", "week4_unit_gains", tmp_path)
    code, said, result = _grade(capsys, tmp_path, "week4", str(folder), "--practice")
    assert code == 1, said
    assert result["score"] == result["max_score"] == 7.5
    assert all(c["status"] == "passed" for c in result["checks"])
    (check,) = result["practice"]["checks"]
    assert check["status"] == "failed"
    assert "week-4 world, turned 142.5 degrees: collided at t = " in check["message"], check["message"]
    assert "FAIL week4.avoid.other_starts practice" in said and "turned 142.5 degrees: collided" in said
    assert "practice: 0 of 1 practice check passed (never part of the total)" in said
    page = (tmp_path / "out" / "week4.html").read_text()
    assert "Practice (not graded)" in page and "turned 142.5 degrees: collided" in page
    assert "practice, not graded" in page  # in place of the points


@pytest.mark.parametrize(("argv", "says"), [
    (["week4", "--solutions", "--practice", "--hidden"], "without --hidden: it runs the practice variants"),
    (["week2", "--solutions", "--practice"], "week 2 has no practice set"),
    (["week4", "--practice", "--batch", "nowhere"], "--practice is for one submission"),
])
def test_practice_refuses_what_it_cannot_do(capsys, argv: list[str], says: str) -> None:
    assert main(argv) == 2
    assert says in " ".join(capsys.readouterr().err.split())


@pytest.mark.slow
@pytest.mark.parametrize(("week", "check_id"), [
    (3, "week3.go_to_goal.other_goals"), (3, "week3.pid.tracking_other_goal"), (5, "week5.blending.hidden"),
    (5, "week5.switching.hidden"), (6, "week6.laps.hidden"), (7, "week7.navigate.other_goals"),
])
def test_the_reference_passes_every_practice_variant(week: int, check_id: str) -> None:
    from grader.grading import grade_submission

    result = grade_submission(week, ROOT / "solutions" / f"week{week}", practice=True, only=check_id)
    (check,) = result["practice"]["checks"]
    assert check["status"] == "passed", check["message"]


def test_remaking_a_practice_set_regrades_no_batch(tmp_path: Path, monkeypatch) -> None:
    """A batch reuses a stored result while its grader fingerprint holds (grader.batch.cache): a new
    practice set, which no official grade runs, keeps it; the code that picks a hidden check's variants
    does not."""
    import shutil

    import grader
    import simiam
    from grader.batch.cache import grader_fingerprint

    junk = shutil.ignore_patterns("__pycache__", "compiled")
    for package in (grader, simiam):
        shutil.copytree(Path(package.__file__).parent, tmp_path / package.__name__, ignore=junk)
        monkeypatch.setattr(package, "__file__", str(tmp_path / package.__name__ / "__init__.py"))
    before = grader_fingerprint()
    data = tmp_path / "grader" / "practice" / "week4.json"
    data.write_text(data.read_text().replace('"turn": 47', '"turn": 45'))
    assert grader_fingerprint() == before
    code = tmp_path / "grader" / "practice" / "__init__.py"
    code.write_text(code.read_text() + "\n# changed\n")
    assert grader_fingerprint() != before


def test_a_plain_grading_says_where_practice_is() -> None:
    import io

    from grader.terminal import print_result

    def said(week: int) -> str:
        out = io.StringIO()
        print_result({"week": week, "status": "graded", "hidden": False, "hidden_checks_not_run": 1,
                      "visible_checks": 3, "checks": [], "score": 0, "max_score": 0}, out)
        return " ".join(out.getvalue().split())

    assert "(grade week4 --practice tries practice variants drawn like them)" in said(4)
    assert "--practice" not in said(2)  # no practice set there


def test_the_engine_refuses_practice_where_there_is_none() -> None:
    """Week 2's hidden check draws its angles from the seed: run "as practice" it would show the hidden
    draw under the practice label."""
    from grader.grading import grade_submission

    with pytest.raises(ValueError, match="week 2 has no practice set"):
        grade_submission(2, ROOT / "solutions" / "week2", practice=True)
