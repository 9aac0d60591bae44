"""How large one answer of the worker may be, and how much of them the grading process holds at once.

The message cap alone (protocol.MAX_MESSAGE, 4 MB) bounds bytes, not what they decode to: a line of
`[[],[],...]` becomes some 20 times its size in Python objects, and a property check keeps every case's
answers until its cases are done (grader.batched_cases), 64 probes to a request. So one student's worker
could make the grading process hold gigabytes. The bounds here are on what an answer holds once decoded:

- one answer: at most MAX_ANSWER_BYTES on the wire, values nested at most MAX_DEPTH deep (as
  protocol.to_json refuses deeper ones), at most MAX_VALUES values (lists, dicts, keys, strings, numbers)
  and MAX_TEXT characters of text, integers no larger in magnitude than MAX_NUMBER, the largest a float
  holds (as to_json): every check may turn a number it is given into a float, and one beyond it would
  raise OverflowError in trusted code (issue 30);
- the answers the grader keeps together (one `probe_many` request, or all the rounds of one property
  check): an AnswerBudget of HELD_VALUES values and HELD_TEXT characters.

The largest honest answer of the course (week 5's blend, 25 calls) is about 3 KB, 200 values, depth 5; an
honest error with 20 frames of non-ASCII code about 110 KB. Both sides apply the per-answer bounds: inside
the worker an honest answer beyond them becomes a short error the student reads ("your code returned a
value too large"), and the grader's side (grader.sandbox.runner) treats a message beyond them as a
protocol violation, found before any trusted code walks the value. `weigh` walks without recursion and
stops at the first bound it passes, so neither a value 700 lists deep nor one of a million items costs more
than the bounds themselves.
"""

from __future__ import annotations

import sys
from typing import Any, NamedTuple

MAX_ANSWER_BYTES = 256 * 1024  # one line from the worker (requests keep protocol.MAX_MESSAGE)
MAX_DEPTH = 32                 # levels below the value, as protocol.to_json
MAX_VALUES = 4096              # lists, dicts, keys, strings, numbers, booleans and nulls of one answer
MAX_TEXT = 64 * 1024           # characters of strings and keys of one answer
MAX_INT_BITS = 1024            # a cheap first test; MAX_NUMBER is the bound
MAX_NUMBER = int(sys.float_info.max)  # the largest integer a float holds: float(n) never overflows within it
HELD_VALUES = 8 * MAX_VALUES   # what one request, or one property check, keeps of a student's answers
HELD_TEXT = 4 * MAX_TEXT


_PLAIN = frozenset((float, bool, type(None)))  # values with nothing to check below them (int: its size)


class OutOfBounds(ValueError):
    """A value beyond one of the bounds; the message says which, in words a student can read."""


class Weight(NamedTuple):
    values: int
    text: int


def weigh(value: Any, max_depth: int = MAX_DEPTH, max_values: int = MAX_VALUES,
          max_text: int = MAX_TEXT) -> Weight:
    """The number of values and characters of text in a decoded JSON value, or OutOfBounds as soon as it
    passes a bound. Only JSON's types count as values: anything else is refused (a decoded message holds
    nothing else; inside the worker, protocol.to_json has already converted the student's value)."""
    values = text = 0
    todo: list[tuple[Any, int]] = [(value, 0)]
    while todo:
        item, depth = todo.pop()
        values += 1
        kind = type(item)
        if kind is str:
            text += len(item)
        elif kind is list or kind is dict:
            if item and depth >= max_depth:
                raise OutOfBounds(f"a value nested more than {max_depth} levels deep")
            if values + len(todo) + (2 * len(item) if kind is dict else len(item)) > max_values:
                raise OutOfBounds(f"a value of more than {max_values} numbers, strings and lists")
            if kind is dict:
                for key, inner in item.items():
                    if type(key) is not str:
                        raise OutOfBounds("a dict whose keys are not strings")
                    todo.append((key, depth + 1))
                    todo.append((inner, depth + 1))
            elif set(map(type, item)) <= _PLAIN:  # a row of numbers (most of a scenario's batch): counted
                values += len(item)                 # at once, within the bound checked just above
            else:
                todo.extend((inner, depth + 1) for inner in item)
        elif kind is int:
            if too_large(item):
                raise OutOfBounds("an integer too large to be a number of this course (no float holds it)")
        elif item is not None and kind is not float and kind is not bool:
            raise OutOfBounds(f"a {kind.__name__}, which JSON does not have")
        if values > max_values:
            raise OutOfBounds(f"a value of more than {max_values} numbers, strings and lists")
        if text > max_text:
            raise OutOfBounds(f"a value holding more than {max_text} characters of text")
    return Weight(values, text)


def too_large(number: int) -> bool:
    """Whether an integer is beyond what a float holds (its bits first: a million-digit one costs no more
    than a comparison)."""
    return number.bit_length() > MAX_INT_BITS or not -MAX_NUMBER <= number <= MAX_NUMBER


_FIELDS = frozenset(("id", "ok", "value", "error"))


def check_message(message: dict) -> None:
    """A decoded message of the worker within the bounds: only an answer's fields, each of them (the
    value, an error's description) within the bounds of one answer."""
    if not _FIELDS.issuperset(message):
        raise OutOfBounds("fields no answer has")
    for field in message.values():
        weigh(field)


class AnswerBudget:
    """What answers kept together may weigh in all: `take` each answer as it arrives, and an answer that
    would pass the budget is refused (OutOfBounds) instead of kept."""

    def __init__(self, values: int = HELD_VALUES, text: int = HELD_TEXT) -> None:
        self.values, self.text = values, text
        self.values_left, self.text_left = values, text

    def take(self, value: Any) -> Any:
        """`value`, counted against the budget; OutOfBounds (and nothing counted) if it does not fit."""
        weight = weigh(value)
        if weight.values > self.values_left or weight.text > self.text_left:
            self.values_left = self.text_left = 0  # the answers after it are refused too: one rule, in order
            raise OutOfBounds(f"answers of more than {self.values} numbers, strings and lists (or "
                              f"{self.text} characters of text) in all, more than the grader keeps "
                              "for one check")
        self.values_left -= weight.values
        self.text_left -= weight.text
        return value
