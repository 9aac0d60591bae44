"""What `grade` prints: student text never reaches the terminal raw; one line per passed check, failures
with their message and replay line, what failed at the end; colour only on a TTY; wrapped to the width."""

from __future__ import annotations

import importlib.util
import io
import re
import unicodedata
from pathlib import Path

import mistakes
import pytest

from grader.cli import main as grade_main
from grader.terminal import print_result
from grader.untrusted import printable

WRONG = Path(__file__).resolve().parents[1] / "data" / "terminal_wrong" / "printables.py"
# OSC (window title), clear screen, cursor up, carriage return, backspace, bell, a one-byte CSI (C1),
# bidi override and isolate, zero-width space, line separator, lone surrogate
HOSTILE = "\x1b]0;owned\x07\x1b[2J\x1b[1A\r\x08\x9b31m\u202e\u2066\u200b\u2028\udcff"
OUR_COLOURS = re.compile(r"\x1b\[(?:32|1;31|33|35|1|2|0)m")


def raw_controls(text: str) -> list[str]:
    """Characters that act on a terminal or reorder text (all but newline), as reprs for the message."""
    return [repr(c) for c in text if c != "\n" and unicodedata.category(c) in ("Cc", "Cf", "Cs", "Zl", "Zp")]


@pytest.fixture(autouse=True)
def _width(monkeypatch) -> None:
    """Every test here sees a 100-column terminal unless it sets its own: the width of the terminal
    pytest happens to run in (or none, under xdist) must not decide a verdict."""
    monkeypatch.setenv("COLUMNS", "100")


def flat(text: str) -> str:
    """Text without any whitespace: what survives wrapping unchanged."""
    return "".join(text.split())


class Tty(io.StringIO):
    def isatty(self) -> bool:
        return True


def _wrong_versions():
    spec = importlib.util.spec_from_file_location("terminal_wrong", WRONG)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return [mod.unchanged, mod.strip_colour_codes, mod.ascii_controls_only]


def test_printable_shows_every_control_and_format_character_as_an_escape() -> None:
    text = printable("before" + HOSTILE + "after\nθ é 😀 ±2π")
    assert raw_controls(text) == []
    # newlines and ordinary non-ASCII text stay as they are
    assert text == ("before\\x1b]0;owned\\x07\\x1b[2J\\x1b[1A\\r\\x08\\x9b31m"
                    "\\u202e\\u2066\\u200b\\u2028\\udcffafter\nθ é 😀 ±2π")
    assert printable("a\r\nb\tc", multiline=False) == "a\\r\\nb c"  # one line: names, ids, paths
    assert printable("a\r\nb") == "a\nb"  # Windows line ends in a student's output are line ends
    for wrong in _wrong_versions():
        assert raw_controls(wrong("before" + HOSTILE + "after")) != [], wrong.__name__


def hostile_result() -> dict:
    return {
        "week": 3, "submission": "week3" + HOSTILE, "seed": 1, "grader_version": "0.1", "isolation": "bwrap",
        "status": "graded", "score": 1.5, "max_score": 3.0, "hidden": False, "hidden_checks_not_run": 2,
        "visible_checks": 3, "notices": ["go_to_goal.py: line 12 edited outside a block" + HOSTILE],
        "checks": [
            {"id": "week3.pid.proportional", "status": "passed", "points": 1.0, "max_points": 1.0,
             "message": "the proportional term is right (25 cases)", "details": {}},
            {"id": "week3.ensure_w.keeps_w", "status": "error", "points": 0.0, "max_points": 1.0,
             "message": "with v = 0.25, w = 3.0 your code raised an error: ValueError: " + HOSTILE,
             "details": {"replay": "grade week3 --check week3.ensure_w.keeps_w --case 'v=0.25,w=3.0'"}},
            {"id": "week3.pid.settle_time", "status": "failed", "points": 0.5, "max_points": 1.0,
             "message": "theta never settled within 10 % of theta_g on the way to (0, -1)\n"
                        "hint: raise Kp, or check the sign of e_k",
             "details": {}},
        ],
    }


def test_the_table_shows_student_text_only_as_visible_escapes() -> None:
    plain, tty = io.StringIO(), Tty()
    print_result(hostile_result(), plain)
    print_result(hostile_result(), tty)
    assert raw_controls(plain.getvalue()) == []
    assert raw_controls(OUR_COLOURS.sub("", tty.getvalue())) == []  # only the table's own colours
    assert "ValueError:\\x1b]0;owned\\x07" in flat(plain.getvalue())
    assert "week3\\x1b]0;owned" in flat(plain.getvalue())


def test_passed_checks_take_one_line_failures_their_message_and_replay_line() -> None:
    out = io.StringIO()
    print_result(hostile_result(), out)
    lines = out.getvalue().splitlines()
    passed = [k for k, line in enumerate(lines) if "week3.pid.proportional" in line]
    assert len(passed) == 1 and lines[passed[0]].split()[0] == "ok"
    assert "the proportional term is right" not in out.getvalue()
    assert lines[passed[0] + 1].split()[0] == "ERROR"  # the next check follows at once
    error = next(k for k, line in enumerate(lines) if line.split()[:2] == ["ERROR", "week3.ensure_w.keeps_w"])
    assert "your code raised an error" in lines[error + 1]
    assert any(line.strip() == "replay: grade week3 --check week3.ensure_w.keeps_w --case 'v=0.25,w=3.0'"
               for line in lines[error + 1:error + 4])
    # a message's own lines stay lines (a hint under the measurement)
    assert any(line.strip() == "hint: raise Kp, or check the sign of e_k" for line in lines)


def test_what_did_not_pass_is_listed_at_the_end() -> None:
    out = io.StringIO()
    print_result(hostile_result(), out)
    tail = out.getvalue().splitlines()[-4:]
    assert tail[0].strip() == "not passed (2 of 3):"
    assert tail[1].split() == ["week3.ensure_w.keeps_w", "0/1", "error"]
    assert tail[2].split() == ["week3.pid.settle_time", "0.5/1", "failed"]
    assert tail[3].strip() == "total: 1.5 / 3"


def test_colour_only_on_a_terminal_and_never_with_no_color(monkeypatch) -> None:
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.setenv("TERM", "xterm-256color")
    tty, pipe = Tty(), io.StringIO()
    print_result(hostile_result(), tty)
    print_result(hostile_result(), pipe)
    assert "\x1b[32mok" in tty.getvalue() and "\x1b[33mERROR" in tty.getvalue()
    assert "\x1b[1;31mFAIL" in tty.getvalue()
    assert "\x1b[" not in pipe.getvalue()
    monkeypatch.setenv("NO_COLOR", "1")
    no_color = Tty()
    print_result(hostile_result(), no_color)
    assert "\x1b[" not in no_color.getvalue()
    assert no_color.getvalue() == pipe.getvalue()


@pytest.mark.parametrize("columns", [60, 100, 160])
def test_lines_wrap_to_the_terminal_width(monkeypatch, columns: int) -> None:
    monkeypatch.setenv("COLUMNS", str(columns))
    result = hostile_result()
    result["checks"][2]["message"] = " ".join(["the heading kept oscillating around theta_g"] * 8)
    out = io.StringIO()
    print_result(result, out)
    lines = out.getvalue().splitlines()
    # a replay command is never wrapped (it is pasted whole); everything else fits
    assert [line for line in lines if len(line) > columns and "replay: " not in line] == []
    assert sum("oscillating" in line for line in lines) >= 8 * 45 // columns  # wrapped, not cut


def test_grade_week_n_prints_student_text_only_as_visible_escapes(tmp_path: Path, capsys) -> None:
    """Single mode end to end: a folder named with escapes, code that raises with escapes in its message."""
    folder = mistakes.build("submissions", "week3_hostile_error", tmp_path, folder_name="week3\x1b]0;x\x07\r")
    code = grade_main(["week3", str(folder), "--check", "week3.ensure_w.keeps_w"])
    out = capsys.readouterr()
    assert code == 1
    assert raw_controls(out.out) == [] and raw_controls(out.err) == []
    assert "week3\\x1b]0;x\\x07\\r" in flat(out.out)  # the folder, visibly
    assert flat("ValueError: <img src=x onerror=window.__pwned=5></script><!-- \\x1b]0;owned\\x07\\x1b[2J"
                "\\r\\u202eko") in flat(out.out)
    missing = tmp_path / "gone\x1b[2J"
    assert grade_main(["week3", str(missing)]) == 2
    assert raw_controls(capsys.readouterr().err) == []


def test_a_reason_shared_by_many_checks_is_printed_once() -> None:
    result = hostile_result()
    why = "this check needs code that did not load: go_to_goal.py:47: syntax error"
    for check in result["checks"][1:]:
        check.update(status="error", message=why, details={})
    out = io.StringIO()
    print_result(result, out)
    text = flat(out.getvalue())  # however wide the terminal of the run (xdist workers have none)
    assert text.count(flat(why)) == 1 and flat("(the same reason as above)") in text


def test_the_hidden_checks_line_says_what_the_weeks_variants_vary() -> None:
    """Each week declares what its hidden checks vary (Week.hidden_variants); the line counting them says
    it, and a result of a week not declared here falls back on the generic words."""
    def line(week: object) -> str:
        out = io.StringIO()
        print_result({**hostile_result(), "week": week}, out)
        return flat(out.getvalue())

    assert flat("2 hidden checks (other goals, drawn per seed) run at official grading") in line(3)
    assert flat("2 hidden checks (either side, other start headings and distances d_fw, drawn per seed) run "
                "at official grading") in line(6)
    assert flat("2 hidden checks (other goals, other worlds, drawn per seed)") in line(99)
