"""What a student's code printed, as the result keeps it: the first lines and the last, the middle cut."""

from __future__ import annotations

from pathlib import Path

import mistakes

from grader.grading import grade_submission
from grader.sandbox.output import cut_middle


def test_cut_middle_keeps_whole_first_and_last_lines() -> None:
    text = "".join(f"line {k}\n" for k in range(1, 2001))
    cut = cut_middle(text, 400)
    assert cut.startswith("line 1\nline 2\n") and cut.endswith("line 1999\nline 2000\n")
    assert len(cut) <= 400
    head, _, rest = cut.partition("\n[... ")
    note, _, tail = rest.partition(" characters cut here ...]\n")
    assert text.startswith(head + "\n") and text.endswith(tail)  # whole lines, from both ends
    assert len(head) + 1 + int(note) + len(tail) == len(text)  # the note counts what is missing
    assert cut_middle("short\n", 400) == "short\n"
    assert cut_middle("x" * 1000, 100).startswith("x" * 20)  # one long line: cut inside it
    assert len(cut_middle("y\n" * 10**6, 4000)) <= 4000


def test_a_student_who_prints_on_every_call_sees_the_first_prints(tmp_path: Path) -> None:
    folder = mistakes.build("submissions", "week2_debug_prints", tmp_path, folder_name="week2")
    result = grade_submission(2, folder, seed=1, only="week2.go_to_angle.reaches_theta_d")
    output = result["student_output"]
    assert result["checks"][0]["status"] == "passed"
    assert output.startswith("debug call 1: v = ")  # where a student looks for their first debug line
    assert "characters cut here" in output and len(output) <= 4000
    last = output.rstrip("\n").rsplit("\n", 1)[1]
    assert last.startswith("debug call ") and int(last.split()[2].rstrip(":")) > 100
