"""WRONG VERSION (tests/sandbox/test_answer_bounds.py): the grader's side before issue 22, when the only
bound on an answer was the 4 MB message cap: no bound on its depth, its values or its text, and no budget
on what a request's or a property check's answers hold together. `install()` puts it back in this process
(`install(monkeypatch.setattr)` in a test)."""

from collections.abc import Callable
from typing import Any


def install(patch: Callable[[Any, str, Any], None] = setattr) -> None:
    from grader.inside import answer_bounds, protocol
    from grader.sandbox import runner

    patch(runner, "MAX_ANSWER_BYTES", protocol.MAX_MESSAGE)
    patch(runner, "check_message", lambda message: None)
    patch(answer_bounds.AnswerBudget, "take", lambda self, value: value)
