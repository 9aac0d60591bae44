"""grader.inside.shorten: the one rule set every capped text is cut by (see its docstring), checked on the
functions and on every caller; the four cutters it replaced (sandbox_wrong.old_cutters) each break a rule."""

from __future__ import annotations

import html
import io
import re
from collections.abc import Callable

import pytest
from sandbox_wrong import old_cutters

from grader.batch import progress
from grader.batch.progress import Progress
from grader.inside import caps, shorten
from grader.inside.shorten import keep_ends, keep_head
from grader.platforms.gradescope import summary_html
from grader.platforms.official import cap
from grader.result_size import bound_result
from grader.sandbox.output import cut_middle

Cut = Callable[[str, int], str]
_NOTE = re.compile(r"\[\.\.\. (\d+) characters cut here \.\.\.\]")
TEXTS = {
    "one line": "x" * 1000,
    "lines": "".join(f"line {k}\n" for k in range(300)),
    "blank lines": "a\n\n\n\n" * 200,
    "multi-byte": "é😀中" * 400,
}
LIMITS = (0, 1, 10, 33, 36, 37, 38, 40, 41, 60, 100, 999)
CUTS: dict[str, Cut] = {
    "keep_head": keep_head,
    "keep_ends": keep_ends,
    "keep_ends whole_lines": lambda t, n: keep_ends(t, n, whole_lines=True),
}


def broken(cut: Cut, text: str, limit: int, *, whole_lines: bool = False) -> list[str]:
    """The rules of grader.inside.shorten that `cut(text, limit)` breaks."""
    out = cut(text, limit)
    problems = []
    if len(out) > limit:
        problems.append(f"{len(out)} characters, over the limit of {limit}")
    notes = list(_NOTE.finditer(out))
    if len(text) <= limit:
        return problems + ([] if out == text else ["text within the limit was changed"])
    if not notes:
        if out != text[:limit] or len(f" {shorten.marker(len(text))}") <= limit:
            problems.append("cut without saying so, though the marker fits")
        return problems
    note = notes[-1]
    head, tail = out[:note.start()], out[note.end():]
    gap = "\n" if whole_lines else " "
    if not head.endswith(gap) or (tail and not tail.startswith(gap)):
        problems.append("the marker is not set off")
    head, tail = head[:-1], tail[1:]
    missing = int(note.group(1))
    own_newline = whole_lines and text[len(head):len(head) + 1] == "\n"  # the head's line end sets it off
    if not (text.startswith(head) and text.endswith(tail)):
        problems.append("what is shown is not the text's start and end")
    elif missing not in {len(text) - len(head) - len(tail) - own_newline}:
        problems.append(f"the marker says {missing} characters cut, "
                        f"{len(text) - len(head) - len(tail) - own_newline} are missing")
    return problems


@pytest.mark.parametrize("limit", LIMITS)
@pytest.mark.parametrize("text", TEXTS.values(), ids=TEXTS.keys())
@pytest.mark.parametrize("name", CUTS)
def test_every_cut_keeps_the_rules(name: str, text: str, limit: int) -> None:
    assert broken(CUTS[name], text, limit, whole_lines="whole_lines" in name) == []


def test_text_within_the_limit_is_the_same_text() -> None:
    text = "short\n"
    assert keep_head(text, 6) is text and keep_ends(text, 6, whole_lines=True) is text


def test_a_marker_longer_than_the_limit_gives_the_start_alone() -> None:
    assert keep_head("abcdefghijkl", 5) == "abcde" and keep_ends("abcdefghijkl", 5) == "abcde"
    assert keep_head("x" * 100, 0) == "" == keep_ends("x" * 100, 0, whole_lines=True)
    marker = " " + shorten.marker(100)                       # exactly room for the marker: nothing else
    assert keep_head("x" * 100, len(marker)) == marker
    assert keep_head("x" * 100, len(marker) - 1) == "x" * (len(marker) - 1)


def test_limits_count_characters_and_never_split_one() -> None:
    text = "😀" * 100                                           # 400 bytes in UTF-8
    for out in (keep_head(text, 50), keep_ends(text, 50), caps.clip(text, 50)):
        assert len(out) <= 50 and out.startswith("😀")
        out.encode("utf-8")                                      # strict: no half character
        assert int(_NOTE.search(out).group(1)) + out.count("😀") == 100


def test_a_cut_exactly_at_a_line_end_keeps_that_line() -> None:
    text = "".join(f"{k:03d}-----\n" for k in range(100))     # 10-character lines
    room = 80 - 2 - len(shorten.marker(len(text)))             # 80 - 2 - 33 = 45: the head slice is 23
    text_head = text[:(room + 1) // 2]
    out = keep_ends(text, 80, whole_lines=True)
    head = out.split("\n[... ")[0]
    assert len(text_head) == 23 and head == "000-----\n001-----"   # back to the line end at 20
    assert broken(CUTS["keep_ends whole_lines"], text, 80, whole_lines=True) == []
    out = keep_ends(text, 2 + len(shorten.marker(len(text))) + 40, whole_lines=True)  # head slice: 20
    assert out.startswith("000-----\n001-----\n[... ")           # both whole lines, no blank one
    assert out.endswith("\n098-----\n099-----\n")


def test_whole_lines_cut_inside_a_line_only_when_a_line_end_would_lose_too_much() -> None:
    out = keep_ends("x" * 1000, 100, whole_lines=True)
    assert out.startswith("x" * 32 + "\n[... 936 characters cut here ...]\n") and out.endswith("x" * 32)
    text = "a" * 30 + "\n" + "b" * 2000                          # the newline is early in the head: kept
    assert keep_ends(text, 100, whole_lines=True).startswith("a" * 30 + "\n[... ")


def test_blank_lines_before_the_cut_are_shown_and_counted() -> None:
    text = "a" + "\n" * 10 + "b" * 1000 + "\nlast\n"
    out = cut_middle(text, 60)
    assert out.startswith("a" + "\n" * 10 + "[... ") and out.endswith("\nlast\n")
    assert not old_cutters.cut_middle(text, 100).startswith("a\n\n")     # the old one dropped them
    assert broken(cut_middle, text, 60, whole_lines=True) == []


@pytest.mark.parametrize("limit", [0, 10, 50])
def test_the_callers_cut_by_the_rules(limit: int) -> None:
    text = "\n".join(f"message {k}" for k in range(500))
    assert broken(lambda t, n: caps.clip(t, n, "default"), text, limit) == []
    assert broken(cap, text, limit) == []
    assert broken(cut_middle, text, limit, whole_lines=True) == []
    bounded = bound_result({"message": text * 100, "score": 1.0}, limit=10_000)
    assert bounded["score"] == 1.0 and len(bounded["message"]) <= 4_000
    assert broken(lambda t, n: keep_ends(t, n), text * 100, 4_000) == []
    assert bounded["message"] == keep_ends(text * 100, 4_000)    # result_size cuts by the same rule


def test_non_strings_are_the_callers_default() -> None:
    assert caps.clip(12, 10, "Error") == "Error" and caps.clip(None, 10) == ""
    assert cap(None, 10) == "" and cap(["a" * 100], 10) == ""


@pytest.mark.parametrize("old, whole_lines, text, limit", [
    (lambda t, n: old_cutters.caps_clip(t, n), False, "x" * 100, 10),           # 100 characters kept
    (old_cutters.official_cap, False, "x" * 200, 0),                           # 0 keeps 160
    (old_cutters.cut_middle, True, "x" * 100, 20),                              # the note alone is over
    (old_cutters.cut_middle, True, "a" + "\n" * 10 + "b" * 1000 + "\nlast\n", 100),  # blank lines lost
    (old_cutters.result_size_clip, False, "x" * 1000, 200),                    # keeps 200 plus the note
    (old_cutters.result_size_clip, False, "x" * 1000, 0),                      # keeps everything
])
def test_the_cutters_it_replaced_each_break_a_rule(old: Cut, whole_lines: bool, text: str,
                                                   limit: int) -> None:
    assert broken(old, text, limit, whole_lines=whole_lines)
    assert broken(CUTS["keep_ends whole_lines" if whole_lines else "keep_ends"], text, limit,
                  whole_lines=whole_lines) == []


def test_gradescope_shows_the_first_and_the_last_printed_lines() -> None:
    printed = "".join(f"debug call {k}\n" for k in range(1, 1001))
    page = summary_html({"week": 2, "status": "graded", "student_output": printed}, {"week": 2})
    shown = html.unescape(page.split("<pre>", 1)[1].split("</pre>", 1)[0])
    assert shown.startswith("debug call 1\n") and shown.endswith("debug call 1000\n") and len(shown) <= 2000


def test_a_batch_warning_line_is_cut_by_the_same_rule() -> None:
    stream = io.StringIO()
    message = "student-007: " + "x" * 5000
    Progress(1, stream=stream, tty=False).message(message)
    line = stream.getvalue().removesuffix("\n")
    assert "\n" not in line and line == keep_head(message, progress.MESSAGE_CHARS)
    assert broken(keep_head, message, progress.MESSAGE_CHARS) == []
