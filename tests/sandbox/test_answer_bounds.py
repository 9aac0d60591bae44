"""Issue 22 items 1 and 2: what one student's answers can make the grading process hold is bounded, and
every answer is checked (bytes, depth, values, text, types) before any trusted code walks it
(grader.inside.answer_bounds).

The attacks replace the worker's sending of answers (tests/data/attacks/forge_answers/ at the session level,
tests/data/attacks/graded/flood_answers.patch and deep_answer.patch end to end). The grader's side as it
was before, where only the 4 MB message cap held, is kept in sandbox_wrong/unbounded_answers.py: a deep
answer crashed a check as a grader error, and a flood of answers made the grading process hold 2.6 GB.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from sandbox_helpers import HONEST, attack, graded_attack, honest_probe
from sandbox_wrong import unbounded_answers

from grader.checks import GRADER_ERROR
from grader.grading import grade_submission
from grader.inside import answer_bounds
from grader.inside.answer_bounds import AnswerBudget, OutOfBounds, weigh
from grader.sandbox.errors import StudentError, WorkerDied
from grader.sandbox.limits import Limits
from grader.sandbox.session import PROBES_PER_REQUEST
from grader.sandbox.validate import BadValue

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
CHECK = "week2.uni_to_diff.round_trip"
LIMITS = Limits(call_seconds=5.0, total_seconds=60.0)
EXTRA_MIB = 32  # what hostile answers may add to an honest grading's peak (the old code: 160 MiB to 2.6 GB)


def _nested(levels: int) -> list:
    value: list = []
    for _ in range(levels):
        value = [value]
    return value


# ---- the bounds themselves ------------------------------------------------------------------------------
def test_weighing_a_value_deeper_than_the_stack_stops_at_the_bound():
    with pytest.raises(OutOfBounds, match="nested more than 32 levels deep"):
        weigh(_nested(200_000))            # recursion would need 200,000 frames
    weigh(_nested(32))                     # as deep as the worker's to_json sends
    with pytest.raises(OutOfBounds, match="nested more than 32"):
        weigh(_nested(33))


@pytest.mark.parametrize("value, words", [
    ([0] * (answer_bounds.MAX_VALUES + 1), "more than 4096 numbers"),
    ({f"k{i}": i for i in range(3000)}, "more than 4096 numbers"),
    (["x" * 40_000, "y" * 40_000], "characters of text"),
    ([2 ** 2000], "integer too large"),
    ({1: 2}, "keys are not strings"),
    ([{1, 2}], "a set, which JSON does not have"),
])
def test_each_bound_of_one_answer(value, words):
    with pytest.raises(OutOfBounds, match=words):
        weigh(value)


def test_the_largest_honest_answers_are_far_within_the_bounds():
    blend = [{"out": [0.15, 12.66], "u_ao_gtg": [-0.51, -0.14], "theta_g": -2.87}] * 25  # week 5, 25 calls
    frames = [{"file": "f" * 100, "line": 10, "function": "g" * 100, "code": "\u00e9" * 200}] * 20
    error = {"type": "ValueError", "message": "\u00e9" * 1000, "file": "a.py", "line": 3, "frames": frames}
    assert weigh(blend).values * 10 < answer_bounds.MAX_VALUES
    assert weigh(error).text * 4 < answer_bounds.MAX_TEXT
    assert len(json.dumps(error)) * 2 < answer_bounds.MAX_ANSWER_BYTES


def test_a_budget_refuses_what_would_pass_it_and_everything_after():
    budget = AnswerBudget(values=10, text=100)
    assert budget.take([1, 2, 3]) == [1, 2, 3]
    with pytest.raises(OutOfBounds, match="more than 10 numbers"):
        budget.take(list(range(7)))
    with pytest.raises(OutOfBounds):
        budget.take(1)


# ---- at the session: a worker that sends what no honest worker sends is stopped ------------------------
@pytest.mark.parametrize("fn, args, words", [
    ("flood", {"size": 4_000_000}, "exceeds the 262144 byte cap"),
    ("flood", {"size": 250_000}, "more than 4096 numbers"),
    ("deep", {"levels": 700}, "nested more than 32 levels deep"),
    ("junk", {}, "fields no answer has"),
])
def test_an_answer_beyond_the_bounds_is_a_protocol_violation(open_session, fn, args, words):
    session = open_session("forge_answers")
    with pytest.raises(WorkerDied, match=words):
        attack(session, fn=fn, **args)
    assert honest_probe(session) == pytest.approx(HONEST)  # a fresh worker, the attack undone
    assert session.starts == 2


def test_an_honest_answer_beyond_the_bounds_is_the_students_error(open_one):
    session = open_one("_honest")
    with pytest.raises(StudentError, match="more than 4096 numbers.*more than the grader takes"):
        session.call("probe", name="echo", args={"value": list(range(5000))})
    with pytest.raises(StudentError, match="characters of text"):
        session.call("probe", name="echo", args={"value": "x" * 100_000})
    with pytest.raises(StudentError, match="bytes as JSON"):  # within the text bound, but escaped
        session.call("probe", name="echo", args={"value": "\u00e9" * 60_000})
    assert honest_probe(session) == pytest.approx(HONEST) and session.starts == 1  # the worker goes on


def test_a_request_keeps_at_most_its_budget_of_answers(open_one):
    session = open_one("_honest")
    wide = list(range(answer_bounds.MAX_VALUES - 1))   # 4096 values with the list itself
    answers = session.probe_many([{"name": "echo", "args": {"value": wide}}] * 12)
    kept = answer_bounds.HELD_VALUES // answer_bounds.MAX_VALUES
    assert answers[:kept] == [wide] * kept
    assert all(isinstance(a, BadValue) and "more than the grader keeps" in str(a) for a in answers[kept:])
    assert len(answers) == 12 <= PROBES_PER_REQUEST and session.starts == 1


# ---- end to end ------------------------------------------------------------------------------------------
def test_a_deep_answer_is_the_students_not_a_grader_error(tmp_path, mode):
    result = grade_submission(2, graded_attack(tmp_path, "deep_answer"), limits=LIMITS, sandbox=mode)
    assert result["status"] == "graded"
    assert not [c["id"] for c in result["checks"] if GRADER_ERROR in c["message"]]
    hit = [c for c in result["checks"] if "nested more than 32 levels deep" in c["message"]]
    assert hit and all(c["points"] == 0 and c["status"] == "error" for c in hit)
    assert "broke the protocol" in hit[0]["message"]


def test_the_old_grader_side_crashed_on_a_deep_answer(tmp_path, monkeypatch, one_mode):
    unbounded_answers.install(monkeypatch.setattr)
    folder = graded_attack(tmp_path, "deep_answer")
    result = grade_submission(2, folder, only=CHECK, limits=LIMITS, sandbox=one_mode)
    check = result["checks"][0]
    assert GRADER_ERROR in check["message"] and "RecursionError" in check["message"]


def _peak(folder: Path, mode: str, wrong: bool = False) -> dict:
    """The check's outcome and the grading process's peak memory, graded in a fresh process."""
    command = [sys.executable, str(HERE / "grading_memory.py"), str(folder), mode, CHECK]
    done = subprocess.run(command + (["--wrong"] if wrong else []), capture_output=True, text=True,
                          check=True, cwd=REPO)
    return json.loads(done.stdout.splitlines()[-1])


@pytest.fixture(scope="module")
def honest_peak() -> dict[str, float]:
    """An honest week-2 grading's peak in each mode (the control)."""
    return {}


@pytest.mark.parametrize("size", [4_000_000, 250_000, 12_000])
def test_flooding_answers_leaves_the_grading_process_within_its_bound(tmp_path, mode, honest_peak, size):
    """4 MB: the issue's answers, each just under the old message cap; 250 KB: under the answer's byte cap,
    beyond its values; 12 KB: within every bound of one answer, so the request's budget is what binds."""
    if mode not in honest_peak:
        control = _peak(REPO / "solutions" / "week2", mode)
        assert control["status"] == "passed", control
        honest_peak[mode] = control["peak_mib"]
    hostile = _peak(graded_attack(tmp_path, "flood_answers", bytes=size), mode)
    assert hostile["points"] == 0 and hostile["status"] in ("failed", "error")
    assert hostile["peak_mib"] < honest_peak[mode] + EXTRA_MIB, hostile


def test_the_old_grader_side_held_what_the_flood_sent(tmp_path, one_mode):
    control = _peak(REPO / "solutions" / "week2", one_mode, wrong=True)
    hostile = _peak(graded_attack(tmp_path, "flood_answers", bytes=250_000), one_mode, wrong=True)
    assert hostile["peak_mib"] > control["peak_mib"] + 4 * EXTRA_MIB, hostile
