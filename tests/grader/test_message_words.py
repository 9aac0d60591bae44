"""The words of messages built from parts (issue 23, "Words and docs"): each test below fails on the
words the grader printed before (kept in the assertions' `not in` halves)."""

from __future__ import annotations

import io

from test_terminal import flat, hostile_result

from grader.properties import _sandbox_words
from grader.sandbox.errors import StudentError
from grader.sentences import then
from grader.terminal import print_result


def test_a_case_and_its_error_are_two_clauses() -> None:
    """The case read straight into the error: "close = 0.06 your code raised an error"."""
    said = _sandbox_words(StudentError("NameError: name 'x' is not defined"), {"close": 0.06})
    assert said.startswith("with close = 0.06, your code raised an error: ")
    assert "0.06 your code" not in said


def test_a_note_after_a_question_gets_no_second_full_stop() -> None:
    """"did you mean 'avoid_obstacles'?. Note:" came from joining with ". " after a question."""
    asked = "no state exists with name 'avoid_obstacle'; did you mean 'avoid_obstacles'?"
    note = "Note: earlier weeks are the course's"
    assert then(asked, note) == f"{asked} {note}"
    assert then("reached in 9.1 s", "Note: x") == "reached in 9.1 s. Note: x"
    assert then("it stopped.", "Note: x") == "it stopped. Note: x"
    assert then("reached", "") == "reached" and then("", "Note: x") == "Note: x"


def test_one_hidden_check_runs_and_two_run() -> None:
    """"1 hidden check (...) run at official grading": the verb agrees with the count."""
    def line(n: int) -> str:
        out = io.StringIO()
        print_result({**hostile_result(), "hidden_checks_not_run": n}, out)
        return flat(out.getvalue())

    assert flat("1 hidden check (other goals, drawn per seed) runs at official grading") in line(1)
    assert flat("drawn per seed) run at official grading") not in line(1)
    assert flat("2 hidden checks (other goals, drawn per seed) run at official grading") in line(2)
