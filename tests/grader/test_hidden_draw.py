"""Issue 21 item 6: the hidden variants a seed runs are spread over their kinds. With a plain sample of 3,
the official seed 2014 ran three week-7 variants turned 0 degrees and never tried another start heading.

The checks themselves are driven (their runs replaced by a recorder), so the draw they really make is the
one judged."""

from __future__ import annotations

from collections.abc import Callable
from types import SimpleNamespace

import pytest

from grader.checks import Context, week4, week6, week7
from grader.hidden import load_hidden
from grader.hidden.draw import draw, heading_quarter, turn_quarter

SEEDS = [2014, *range(60)]
FAKE_RUN = SimpleNamespace(problem=None, trace_key=None, sandbox_error=None)


def drawn_by_the_check(week: int, seed: int, monkeypatch: pytest.MonkeyPatch) -> list[tuple]:
    """The variants the week's hidden check runs for `seed`, as the parts it varies."""
    seen: list[tuple] = []
    ctx = Context(week=week, seed=seed, session=None, hidden=True)
    if week == 7:
        def turned(world, goal, turn, of):
            seen.append((turn, of, goal))
            return world, goal
        monkeypatch.setattr(week7, "turned", turned)
        monkeypatch.setattr(week7, "navigate", lambda *a: (True, "reached", {}, FAKE_RUN))
        week7.other_goals(ctx)
    elif week == 6:
        def laps(ctx, check_id, direction, theta0, d_fw, label):
            seen.append((direction, theta0, d_fw))
            return True, "two laps", {}, FAKE_RUN
        monkeypatch.setattr(week6, "_laps", laps)
        week6.hidden_laps(ctx)
    else:
        def variant(world, turn, of, mirror):
            seen.append((turn, of, mirror))
            return world
        monkeypatch.setattr(week4, "_variant", variant)
        monkeypatch.setattr(week4, "_avoid", lambda *a: (True, "no collision", {}, FAKE_RUN))
        week4.other_starts(ctx)
    return seen


def kinds(week: int, part: Callable[[dict], object]) -> int:
    """How many values of `part` the week's hidden set holds (a set may lack some start headings)."""
    return len({part(v) for v in load_hidden(week)["variants"]})


@pytest.mark.parametrize("seed", SEEDS)
def test_week7_tries_three_start_headings(seed: int, monkeypatch: pytest.MonkeyPatch) -> None:
    drawn = drawn_by_the_check(7, seed, monkeypatch)
    headings = min(3, kinds(7, lambda v: turn_quarter(v["turn"], v["of"])))
    assert len(drawn) == 3 and len({turn_quarter(turn, of) for turn, of, _ in drawn}) == headings, drawn


@pytest.mark.parametrize("seed", SEEDS)
def test_week6_tries_both_walls_and_three_start_quarters(seed: int, monkeypatch: pytest.MonkeyPatch) -> None:
    drawn = drawn_by_the_check(6, seed, monkeypatch)
    assert len(drawn) == 3 and {d for d, _, _ in drawn} == {"left", "right"}, drawn
    quarters = min(3, kinds(6, lambda v: heading_quarter(v["theta0"])))
    assert len({heading_quarter(theta0) for _, theta0, _ in drawn}) == quarters, drawn


@pytest.mark.parametrize("seed", SEEDS)
def test_week4_tries_three_start_quarters_mirrored_and_not(seed: int,
                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    drawn = drawn_by_the_check(4, seed, monkeypatch)
    assert len(drawn) == 3 and len({turn_quarter(turn, of) for turn, of, _ in drawn}) == 3, drawn
    assert {mirror for _, _, mirror in drawn} == {False, True}, drawn


def test_every_kind_is_drawn_over_the_seeds_and_a_seed_draws_the_same() -> None:
    """Stratified, not fixed: over many seeds every variant of week 7 runs some time, and one seed always
    runs the same three."""
    variants = load_hidden(7)["variants"]
    kind = lambda v: (turn_quarter(v["turn"], v["of"]),)   # noqa: E731 - as the check declares it
    ran = {str(v) for seed in range(400) for v in draw(variants, 3, f"{seed}:week7-variants", kind)}
    assert ran == {str(v) for v in variants}
    assert draw(variants, 3, "2014:week7-variants", kind) == draw(variants, 3, "2014:week7-variants", kind)
    assert len(draw(variants[:2], 3, "x", kind)) == 2               # fewer variants than asked: all of them
