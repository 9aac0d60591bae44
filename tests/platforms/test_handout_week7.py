"""Week 7's handout ships week 6's follow-wall settings filled in (`self.fw_direction = "left"`), a line the
week-7 automaton's solution also holds: a line of an earlier week's shipped block is no leak, while the
automaton's own lines still are."""

from __future__ import annotations

from mistakes import ROOT

from grader.platforms.handout import handout_files, leaks


def test_an_earlier_weeks_shipped_line_is_no_leak_of_this_weeks_answer():
    files = handout_files(7, ROOT)
    assert 'self.fw_direction = "left"' in files["qb_supervisor.py"]  # week 6's block, shipped filled
    assert leaks(7, files, ROOT) == []


def test_the_automatons_own_lines_are_still_a_leak():
    files = handout_files(7, ROOT)
    files["qb_supervisor.py"] += "\nif sum(ir_distances[0:3]) < sum(ir_distances[2:5]):\n    pass\n"
    found = leaks(7, files, ROOT)
    assert any("ir_distances[2:5]" in f for f in found), found
