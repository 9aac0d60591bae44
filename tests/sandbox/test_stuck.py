"""Where a timed-out call was stuck: the file, line and function in the timeout message, in both isolation
modes; a submission that silences or forges the stack dump only loses the location (never a crash, never
text outside the expected pattern)."""

from __future__ import annotations

import re
import time
from pathlib import Path

import pytest
from sandbox_helpers import ATTACKS, HONEST, attack, honest_probe
from sandbox_wrong import naive

from grader.sandbox.errors import StudentTimeout
from grader.sandbox.stuck import MAX_DUMP_BYTES, Stuck, find_stuck, qualified_name

# The short limit goes only to the call that is stuck (attack's `timeout`); loading and the fresh worker's
# honest call keep the helpers' LIMITS, far above the milliseconds they take with both cores busy.
STUCK_SECONDS = 0.4
PLAIN = "no answer within 0.4 s, the time limit per call"
# The only shape a timeout message may have: the plain reason, optionally one checked location.
SHAPE = re.compile(re.escape(PLAIN) + r"(; it was still running at [A-Za-z_][A-Za-z0-9_]*\.py:\d+ "
                   r"(in [A-Za-z_][A-Za-z0-9_.]*|at module level) "
                   r"\(an endless loop or a long wait\?\))?")


def marked_line(attack_name: str, marker: str) -> int:
    """Line number of `# ... STUCK: <marker>` in the attack's differential_drive.py."""
    lines = (ATTACKS / attack_name / "differential_drive.py").read_text().splitlines()
    return next(i for i, text in enumerate(lines, 1) if text.endswith(f"STUCK: {marker}"))


def timeout_of(session, **args) -> StudentTimeout:
    began = time.monotonic()
    with pytest.raises(StudentTimeout) as caught:
        attack(session, timeout=STUCK_SECONDS, **args)
    print(f"timed out and killed after {time.monotonic() - began:.2f} s (limit {STUCK_SECONDS} s)")
    return caught.value


# ---- in the worker, both isolation modes ------------------------------------------------------------------
@pytest.mark.parametrize("how", ["spin", "doze"])
def test_the_timeout_names_the_file_line_and_method_where_the_code_was_stuck(open_session, how):
    session = open_session("stuck")
    exc = timeout_of(session, how=how)
    line = marked_line("stuck", how)
    assert (exc.file, exc.line, exc.function) == ("differential_drive.py", line, f"Spinner.{how}")
    assert exc.message == (f"{PLAIN}; it was still running at differential_drive.py:{line} in "
                           f"Spinner.{how} (an endless loop or a long wait?)")
    assert honest_probe(session) == pytest.approx(HONEST)  # a fresh worker answers the next call


def test_a_worker_that_takes_the_dump_signal_late_is_still_located(open_session):
    """On a loaded machine a spinning worker may get the CPU (and so take the dump signal) only well after
    the deadline. Here it blocks the signal until 0.6 s of CPU time after the deadline: the grader waits for
    the signal to be taken (up to DUMP_PENDING_SECONDS, 2 s of the worker's own time), not a fixed 0.25 s
    from sending it, which lost this."""
    session = open_session("stuck")
    exc = timeout_of(session, how="late", seconds=STUCK_SECONDS + 0.6)
    assert (exc.file, exc.line, exc.function) == ("differential_drive.py", marked_line("stuck", "late"),
                                                  "Spinner.late")
    assert honest_probe(session) == pytest.approx(HONEST)


@pytest.mark.parametrize("how", ["ignore", "default", "answer"])
def test_silencing_the_dump_only_loses_the_location(open_session, how):
    session = open_session("silence_dump")
    exc = timeout_of(session, how=how)
    assert exc.message == PLAIN and (exc.file, exc.line, exc.function) == (None, None, None)
    assert honest_probe(session) == pytest.approx(HONEST)


def test_a_forged_dump_written_before_the_loop_is_discarded(open_session):
    session = open_session("forge_dump")
    exc = timeout_of(session, how="once")
    assert (exc.file, exc.line) == ("differential_drive.py", marked_line("forge_dump", "forge"))
    assert SHAPE.fullmatch(exc.message)


@pytest.mark.parametrize("how", ["flood", "trickle"])
def test_a_dump_forged_without_end_never_puts_foreign_text_in_the_message(open_session, how):
    session = open_session("forge_dump")
    exc = timeout_of(session, how=how)
    assert SHAPE.fullmatch(exc.message), exc.message
    assert exc.file in (None, "differential_drive.py")
    # Reading the dump is bounded: a writer that never pauses cannot keep the grader waiting (it did:
    # one byte every 5 ms held a reader that waited for 20 ms of silence for minutes).
    assert session.seconds_used < STUCK_SECONDS + 3.0
    assert honest_probe(session) == pytest.approx(HONEST)


# ---- the parser alone (untrusted text in, a checked place or None out) ----------------------------------
SOURCE = '''\
import math


class GoToGoal:
    class Inner:
        def execute(self):
            while True: pass


def helper():
    return [x for x in range(3)]
'''


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    (tmp_path / "go_to_goal.py").write_text(SOURCE)
    return tmp_path


def dump(*threads: tuple[int, list[str]]) -> bytes:
    text = ""
    for ident, frames in threads:
        text += f"Thread 0x{ident:016x} (most recent call first):\n"
        text += "".join(f"  {frame}\n" for frame in frames) + "\n"
    return text.encode()


def test_the_innermost_student_frame_of_the_serving_thread_wins(folder):
    data = dump((7, ['File "/submission/go_to_goal.py", line 11 in helper']),      # a student thread
                (1, ['File "/usr/lib/python3/numpy/core.py", line 3 in dot',       # trusted frame on top
                     'File "/submission/go_to_goal.py", line 7 in execute',
                     'File "/submission/go_to_goal.py", line 11 in helper',
                     'File "/grader/inside/worker_loop.py", line 58 in op_probe']))
    assert find_stuck(data, "/submission", folder, 1) == Stuck("go_to_goal.py", 7, "GoToGoal.Inner.execute")
    assert find_stuck(data, "/submission", folder, 99) == Stuck("go_to_goal.py", 11, "helper")
    place = Stuck("go_to_goal.py", 7, "GoToGoal.Inner.execute")
    assert str(place) == "go_to_goal.py:7 in GoToGoal.Inner.execute"
    assert str(Stuck("go_to_goal.py", 1, "<module>")) == "go_to_goal.py:1 at module level"


@pytest.mark.parametrize("frame", [
    'File "/elsewhere/go_to_goal.py", line 7 in execute',          # not the submission folder
    'File "/submission/../submission/go_to_goal.py", line 7 in execute',
    'File "/submission/sub/go_to_goal.py", line 7 in execute',
    'File "/submission/missing.py", line 7 in execute',            # no such file in the submission
    'File "/submission/go_to_goal.py", line 12 in execute',        # past the end of the file
    'File "/submission/go_to_goal.py", line 0 in execute',
    'File "/submission/go_to_goal.py", line 7 in exec<ute>',       # not an identifier
    'File "/submission/go_to_goal.py", line 7 in execute; more',
    'File "/submission/go_to_goal.py", line 7 in <img src=x>',
    'File "/submission/go_to_goal.py", line 7 in execute ',
    'File "/submission/go_to_goal.py", line 99999999 in execute',
])
def test_frames_that_are_not_a_real_place_in_the_submission_are_ignored(folder, frame):
    assert find_stuck(dump((1, [frame])), "/submission", folder, 1) is None


def test_a_frame_past_the_size_cap_is_not_read(folder):
    frame = 'File "/submission/go_to_goal.py", line 7 in execute'
    padding = b"x" * MAX_DUMP_BYTES + b"\n"
    assert find_stuck(dump((1, [frame])), "/submission", folder, 1) is not None
    assert find_stuck(padding + dump((1, [frame])), "/submission", folder, 1) is None


def test_frames_outside_a_thread_header_and_binary_junk_are_ignored(folder):
    frame = b'  File "/submission/go_to_goal.py", line 7 in execute\n'
    assert find_stuck(frame, "/submission", folder, 1) is None
    assert find_stuck(b"\xff\x00" + frame + dump((1, [])), "/submission", folder, 1) is None


def test_the_naive_reading_is_fooled_by_the_forged_dump_the_strict_one_is_not(folder):
    forged = dump((1, ['File "/submission/go_to_goal.py", line 99999 in <script>alert(1)</script>']))
    assert naive.find_stuck(forged, "/submission") == ("go_to_goal.py", 99999, "<script>alert(1)</script>")
    assert find_stuck(forged, "/submission", folder, 1) is None


def test_qualified_names_come_from_the_source_not_the_dump():
    assert qualified_name(SOURCE, 7, "execute") == "GoToGoal.Inner.execute"
    assert qualified_name(SOURCE, 11, "helper") == "helper"
    assert qualified_name(SOURCE, 11, "<listcomp>") == "<listcomp>"
    assert qualified_name(SOURCE, 7, "other") == "other"   # the name must match the def around the line
    assert qualified_name("def broken(:\n", 1, "broken") == "broken"
